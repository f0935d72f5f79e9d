//! The Z-buffer: one rasterizer (`zbuffer`) hands covered pixels, eight at a time
//! (`fragments`), to a shader; Gouraud lights the vertices and interpolates the colour, Phong
//! interpolates the normal and lights every pixel.

pub mod fragments;
pub mod gouraud;
pub mod phong;
pub mod zbuffer;
