#pragma once
// JSON pieces of metadata.json (nlohmann::json stays out of the public headers).
#include <string>

#include "core/camera.h"
#include "core/rigid3.h"
#include "tools/sim/sim_options.h"

namespace sacfuse::sim {

// Serialised JSON text (compact) of every option value.
std::string SimOptionsJson(const SimOptions& options);
// {"qw","qx","qy","qz","tx","ty","tz","center":[x,y,z]} of a cam_from_world pose.
std::string PoseJson(const Rigid3d& cam_from_world);
// {"model":"PINHOLE","width","height","fx","fy","cx","cy"}.
std::string CameraJson(const PinholeCamera& camera);

}  // namespace sacfuse::sim
