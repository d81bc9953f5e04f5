//! Where a luminaire hangs and where it points: LM-72 aiming (CCE system).
//!
//! A luminaire's own frame is the frame of [`crate::model::frame`] (C0 = +x,
//! C90 = +y, nadir γ = 0 along −z). Installed, its frame is turned by
//! `R = Rz(orient) · Ry(−tilt) · Rx(roll) · Rz(spin)` (LM-72 CCE order as
//! AGi32 documents it: orient about the world Z, then tilt about the local
//! Y, then roll about the local X, then spin about the local Z; every angle
//! counter-clockwise about its axis seen from the axis' tip, except tilt,
//! which is signed so that a positive tilt swings the nadir towards the
//! local +X, i.e. the C0 side). All zeros: nadir down, C0 along world +X.
//!
//! A world vector `w` is `R · l` for the luminaire-frame vector `l`;
//! [`Pose::to_local`] undoes the rotation (`l = Rᵀ · w`), after which the
//! angles come from [`crate::model::frame::angles`].

use glam::{DMat3, DVec3};
use serde::Serialize;

use crate::model::frame::sin_cos_deg;

/// LM-72 aiming angles, degrees.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Aim {
    /// Rotation about the world Z axis, counter-clockwise from above, degrees.
    pub orient: f64,
    /// Rotation about the local Y axis, degrees; positive swings the nadir towards local +X (C0).
    pub tilt: f64,
    /// Rotation about the local X axis, degrees; positive swings the nadir towards local +Y (C90).
    pub roll: f64,
    /// Rotation about the local Z axis (the luminaire's own axis), counter-clockwise, degrees.
    pub spin: f64,
}

/// Rotation about X by `a` degrees (right-handed).
fn rot_x(a: f64) -> DMat3 {
    let (s, c) = sin_cos_deg(a);
    DMat3::from_cols(DVec3::X, DVec3::new(0.0, c, s), DVec3::new(0.0, -s, c))
}

/// Rotation about Y by `a` degrees (right-handed).
fn rot_y(a: f64) -> DMat3 {
    let (s, c) = sin_cos_deg(a);
    DMat3::from_cols(DVec3::new(c, 0.0, -s), DVec3::Y, DVec3::new(s, 0.0, c))
}

/// Rotation about Z by `a` degrees (right-handed).
fn rot_z(a: f64) -> DMat3 {
    let (s, c) = sin_cos_deg(a);
    DMat3::from_cols(DVec3::new(c, s, 0.0), DVec3::new(-s, c, 0.0), DVec3::Z)
}

impl Aim {
    /// The rotation taking luminaire-frame vectors to world vectors.
    pub fn rotation(&self) -> DMat3 {
        rot_z(self.orient) * rot_y(-self.tilt) * rot_x(self.roll) * rot_z(self.spin)
    }

    /// The aim that points the nadir from `from` at `target` (world, metres),
    /// with C0 in the vertical plane through both (orient then tilt only).
    /// `None` when the two points coincide or are not finite.
    pub fn at(from: DVec3, target: DVec3) -> Option<Aim> {
        let d = (target - from).try_normalize()?;
        let (c, gamma) = crate::model::frame::unit_angles(d);
        // In the world frame, the nadir after orient o and tilt t is
        // (sin t cos o, sin t sin o, −cos t): the luminaire-frame angles of d.
        Some(Aim {
            orient: c,
            tilt: gamma,
            roll: 0.0,
            spin: 0.0,
        })
    }
}

/// An installed luminaire: its photometric centre (world, metres) and the
/// rotation of its frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Photometric centre, world coordinates, metres.
    pub position: DVec3,
    /// Luminaire frame to world (orthonormal).
    pub rotation: DMat3,
}

impl Pose {
    /// A pose at `position` (metres) turned by `aim`.
    pub fn new(position: DVec3, aim: Aim) -> Self {
        Self {
            position,
            rotation: aim.rotation(),
        }
    }

    /// A world vector expressed in the luminaire frame (undoes the aim).
    #[inline]
    pub fn to_local(&self, world: DVec3) -> DVec3 {
        self.rotation.transpose() * world
    }

    /// A luminaire-frame vector in world coordinates.
    #[inline]
    pub fn to_world(&self, local: DVec3) -> DVec3 {
        self.rotation * local
    }

    /// A luminaire-frame point (metres from the photometric centre) in world coordinates.
    #[inline]
    pub fn point_to_world(&self, local: DVec3) -> DVec3 {
        self.position + self.rotation * local
    }

    /// The world direction of the nadir (γ = 0).
    pub fn nadir(&self) -> DVec3 {
        self.to_world(crate::model::frame::direction(0.0, 0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::frame::direction;

    fn close(a: DVec3, b: DVec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn each_angle_turns_the_documented_way() {
        let nadir = direction(0.0, 0.0);
        let c0 = direction(0.0, 90.0);
        let r = |a: Aim| a.rotation();
        assert!(close(r(Aim::default()) * nadir, -DVec3::Z));
        assert!(close(r(Aim::default()) * c0, DVec3::X));
        // orient 90: C0 points to world +Y.
        let o = Aim {
            orient: 90.0,
            ..Default::default()
        };
        assert!(close(r(o) * c0, DVec3::Y));
        // tilt 90: nadir to +X.
        let t = Aim {
            tilt: 90.0,
            ..Default::default()
        };
        assert!(close(r(t) * nadir, DVec3::X));
        // roll 90: nadir to +Y.
        let rl = Aim {
            roll: 90.0,
            ..Default::default()
        };
        assert!(close(r(rl) * nadir, DVec3::Y));
        // spin 90 leaves the nadir, turns C0 to +Y.
        let s = Aim {
            spin: 90.0,
            ..Default::default()
        };
        assert!(close(r(s) * nadir, -DVec3::Z) && close(r(s) * c0, DVec3::Y));
        // Order: orient 90 then tilt 90 sends the nadir to world +Y.
        let ot = Aim {
            orient: 90.0,
            tilt: 90.0,
            ..Default::default()
        };
        assert!(close(r(ot) * nadir, DVec3::Y));
    }

    #[test]
    fn aim_at_points_the_nadir_at_the_target() {
        let from = DVec3::new(1.0, 2.0, 8.0);
        for target in [
            DVec3::new(5.0, -3.0, 0.0),
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(-4.0, 2.0, 12.0),
        ] {
            let pose = Pose::new(from, Aim::at(from, target).unwrap());
            assert!(close(pose.nadir(), (target - from).normalize()), "{target}");
            let back = pose.to_local(pose.to_world(DVec3::new(0.3, -0.2, 0.9)));
            assert!(close(back, DVec3::new(0.3, -0.2, 0.9)));
        }
        assert!(Aim::at(from, from).is_none());
    }
}
