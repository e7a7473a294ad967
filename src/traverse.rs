//! Traversals: breadth- and depth-first order, connected components, shortest paths.
