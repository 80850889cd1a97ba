#pragma once
// Which camera-file syntax a path names (internal to io/camera_file*.cc): by extension, .yaml/.yml or .csv.
#include <string>

namespace sacfuse {

enum class CameraFileFormat { kYaml, kCsv };

// Throws InputError naming the path for any other extension.
CameraFileFormat CameraFileFormatOf(const std::string& path);

// The rotation-matrix fields r11..r33, row-major.
inline constexpr const char* kRotationKeys[9] = {"r11", "r12", "r13", "r21", "r22", "r23", "r31", "r32", "r33"};

}  // namespace sacfuse
