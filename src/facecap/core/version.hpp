#pragma once
namespace facecap {
inline constexpr const char* kFacecapVersion = "0.1.0";
}  // namespace facecap
