//! Reading and writing mesh files: one format per file, dispatch by extension.
