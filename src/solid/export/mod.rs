//! Mesh export: OBJ, binary PLY, binary STL, binary glTF (.glb), from one
//! [`Mesh`]; every file is written atomically through
//! [`crate::formats::write_atomic`].
pub mod glb;
pub mod obj;
pub mod ply;
pub mod stl;
