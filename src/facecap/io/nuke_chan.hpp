#pragma once
// Nuke's .chan files (`track --chan`): one line per keyed frame,
// `frame tx ty tz rx ry rz [vfov]`, the translation in the scene's units, the
// rotation in degrees about x, y and z, applied in Nuke's default order ZXY
// (z first: the matrix Ry Rx Rz), and for a camera its vertical field of view
// in degrees. Nuke's Camera and Axis nodes ("import chan file"), Houdini and
// Blender's Nuke .chan add-on read them; Nuke's space is y up, a camera
// looking down its -z axis.
#include <optional>
#include <string>

#include "facecap/core/geometry.hpp"

namespace facecap {

// (rx, ry, rz) in degrees with rotation = Ry(ry) Rx(rx) Rz(rz), rx in
// [-90, 90]; at rx = +-90 (gimbal lock) rz is 0 and ry takes the rest.
Vec3d euler_zxy_degrees(const Mat3d& rotation);
// The rotation those angles stand for.
Mat3d rotation_from_euler_zxy_degrees(const Vec3d& degrees);

// One line of a .chan file (with its newline); `vfov_deg` for a camera.
std::string chan_line(int frame, const Vec3d& translate, const Vec3d& rotate_deg,
                      std::optional<double> vfov_deg = std::nullopt);

}  // namespace facecap
