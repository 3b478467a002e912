#include "scene/error.h"

namespace clipblur {

std::string FileLoc::toString() const {
    if (file.empty()) return {};
    if (line <= 0) return file;
    return file + ":" + std::to_string(line) + ":" + std::to_string(column);
}

static std::string formatWhat(const FileLoc& loc, const std::string& message) {
    std::string where = loc.toString();
    return where.empty() ? message : where + ": " + message;
}

Error::Error(ExitCode code, std::string message, FileLoc loc)
    : std::runtime_error(formatWhat(loc, message)),
      code_(code),
      loc_(std::move(loc)),
      message_(std::move(message)) {}

void throwConfigError(const FileLoc& loc, std::string_view message) {
    throw Error(ExitCode::Config, std::string(message), loc);
}

void throwSceneError(const FileLoc& loc, std::string_view message) {
    throw Error(ExitCode::Scene, std::string(message), loc);
}

}  // namespace clipblur
