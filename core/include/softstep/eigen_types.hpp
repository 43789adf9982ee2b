// Eigen types that cross the boundary between the library and the program that uses it.
//
// The library may be built for AVX2 (the release preset) and the program without any -march
// (as the README's example is): Eigen then chooses a different alignment on each side (32
// bytes against 16). A dynamic vector allocated inside the library with 32-byte alignment goes
// through Eigen's own aligned malloc, which the program's Eigen frees with plain free():
// "double free or corruption" (issue 17). Fixed-size types over 16 bytes would also change
// their layout. Every Eigen member or return value of the public headers is therefore one of:
//  - a type Eigen never over-aligns (Vector3d, Matrix3d: sizes that are not a multiple of 16);
//  - a DontAlign type from here, whose storage is plain malloc/free and whose layout is the
//    same under any flags;
//  - Eigen::SparseMatrix, whose storage is malloc and new[] on every build.
// They convert implicitly to and from the ordinary Eigen types. The code Eigen inlines into both
// sides must also agree: the CMake target softstep::softstep defines EIGEN_MAX_ALIGN_BYTES=16 and
// EIGEN_MALLOC_ALREADY_ALIGNED=0 for the library and every program that links it (a program
// built without CMake passes both itself; core/CMakeLists.txt says why).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace softstep {

// A vector of any length, doubles.
using VectorX = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::DontAlign>;
// Six doubles: a body's linear then angular velocity.
using Vector6 = Eigen::Matrix<double, 6, 1, Eigen::DontAlign>;
// Orientation (unaligned: Quaterniond is 16-byte aligned with SSE, 32 with AVX).
using Quaternion = Eigen::Quaternion<double, Eigen::DontAlign>;

}  // namespace softstep
