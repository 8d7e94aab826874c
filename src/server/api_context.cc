#include "server/api_context.h"

#include "common/json_file.h"

namespace dynosize::server {

std::string ErrorBody(const std::string& message, int exit_code) {
  Json j;
  j["error"] = message;
  j["exit_code"] = exit_code;
  return j.dump() + "\n";
}

}  // namespace dynosize::server
