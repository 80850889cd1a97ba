#include "io/json_text.h"

#include <nlohmann/json.hpp>

namespace sacfuse {

std::string JsonText(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', /*ensure_ascii=*/false, nlohmann::json::error_handler_t::replace);
}

std::string ValidUtf8(const std::string& text) {
  return nlohmann::json::parse(JsonText(nlohmann::json(text))).get<std::string>();
}

}  // namespace sacfuse
