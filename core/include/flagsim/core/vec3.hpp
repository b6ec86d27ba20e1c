#pragma once
// 3-vectors of the simulation: positions in m, velocities in m/s, forces in N.
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

namespace flagsim {

using Vec3 = Eigen::Vector3d;

}  // namespace flagsim
