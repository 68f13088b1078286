// SPDX-License-Identifier: MIT
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace impulse
{

/// All of impulse works in double precision: the reference scenes ask for 1e-9 conservation.
using Real = double;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
/// Unit quaternion; Eigen stores (x, y, z, w) but constructs as Quat(w, x, y, z).
using Quat = Eigen::Quaterniond;

/// A rigid placement: centre of mass (or body origin) and orientation, world frame.
struct Pose
{
    Vec3 position = Vec3::Zero();
    Quat orientation = Quat::Identity();
    Mat3 rotation = Mat3::Identity(); ///< rotation matrix of `orientation`, kept in step with it

    /// Builds a pose and its rotation matrix.
    static Pose from(const Vec3& position, const Quat& orientation)
    {
        return {position, orientation, orientation.toRotationMatrix()};
    }
    /// Body-frame point to world frame.
    Vec3 toWorld(const Vec3& pointLocal) const { return position + rotation * pointLocal; }
    /// World-frame point to body frame.
    Vec3 toLocal(const Vec3& pointWorld) const { return rotation.transpose() * (pointWorld - position); }
};

} // namespace impulse
