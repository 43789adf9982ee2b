#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

// Quaternion (unaligned on purpose: see eigen_types.hpp). A plain Eigen::Quaterniond converts
// to and from it implicitly.
#include "softstep/eigen_types.hpp"

namespace softstep {

enum class BodyType {
  Static,     // never moves, infinite mass
  Kinematic,  // moves with the velocity the user sets, infinite mass, feels no force
  Dynamic,    // moves under gravity and constraints
};

// Everything a body is. Units: SI (m, kg, s, rad).
struct BodyDef {
  BodyType type = BodyType::Dynamic;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();          // centre of mass, world frame, m
  Quaternion orientation = Quaternion::Identity();             // body to world, unit
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // m/s
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad/s, world frame
  double mass = 1.0;  // kg, > 0 for a dynamic body; ignored for static and kinematic
  // Inertia tensor about the centre of mass in the body frame, kg m^2, symmetric positive
  // definite for a dynamic body. Default: a solid 1 kg sphere of radius 0.1 m.
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity() * 0.004;
  double gravity_scale = 1.0;    // multiplies the world's gravity, any finite value
  double linear_damping = 0.0;   // 1/s, >= 0: v' = -c v
  double angular_damping = 0.0;  // 1/s, >= 0
  bool never_sleep = false;      // keeps the body, and every island it joins, awake
  // The caller's own value (an integer, or a pointer as std::uintptr_t), kept with the body
  // and never read, validated or hashed by softstep (World::user_data).
  std::uint64_t user_data = 0;
};

// Inertia of a solid sphere, kg m^2 (a helper for the common case).
inline Eigen::Matrix3d solid_sphere_inertia(double mass, double radius) {
  return Eigen::Matrix3d::Identity() * (0.4 * mass * radius * radius);
}

// Inertia of a solid box of full side lengths (x, y, z), kg m^2, in the box's frame.
inline Eigen::Matrix3d solid_box_inertia(double mass, const Eigen::Vector3d& size) {
  const Eigen::Vector3d s2 = size.cwiseProduct(size);
  return Eigen::Vector3d(s2.y() + s2.z(), s2.x() + s2.z(), s2.x() + s2.y()).asDiagonal() *
         (mass / 12.0);
}

}  // namespace softstep
