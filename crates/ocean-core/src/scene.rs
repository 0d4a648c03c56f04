//! Scene files. TO BE WRITTEN.
