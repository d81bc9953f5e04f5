//! stl
