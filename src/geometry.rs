//! Geometry over positions: the point trait and measures (lengths, areas, normals).
