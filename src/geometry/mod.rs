//! Geometry: fixed-point vectors and matrices, sine and cosine, meshes, the observer camera.
//!
//! Role in the pipeline: the first stage, producing observer-frame coordinates.
//!
//! One concept per module: [`fixed`] (the formats: [`Coord`](fixed::Coord) = I16F16 for
//! positions, [`Linear`](fixed::Linear) = I8F24 for matrix entries, [`Unit`](fixed::Unit) =
//! I2F30 for sine/cosine), [`trig`] ([`BinaryAngle`](trig::BinaryAngle): 2^32 per turn),
//! [`vector`] ([`Vec3`](vector::Vec3)), [`matrix`] ([`Affine3`](matrix::Affine3)), [`camera`]
//! (the course's observer `(Ω, (W, V, U))` and lens), [`mesh`] (vertex and polygon tables,
//! normals, back-face culling) and [`generators`] (cube, UV sphere, hollow prism, torus).
//!
//! ## Axes (stated once here)
//! The **world** is right-handed: `x` right, `y` up, `z` toward the viewer (SCENES.md). The
//! **observer frame** is the course's `(Ω, (W, V, U))`: `x` along `W` (screen right), `y` along
//! `V` (screen up), `z` along `U` (the view direction, depth). Because it keeps `y` up and `z`
//! forward it is **left-handed**; see [`camera`].

pub mod camera;
pub mod fixed;
pub mod generators;
pub mod matrix;
pub mod mesh;
pub mod trig;
pub mod vector;
