//! (under construction)
pub mod eigen;
pub mod eigen_dense;
pub mod eigen_lanczos;
pub mod eigen_norm;
pub mod eigen_shift;
pub mod eigen_sym;
