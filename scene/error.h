#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace clipblur {

// Where a value came from in a job file; line and column are 1-based, 0 means unknown.
struct FileLoc {
    std::string file;
    int line = 0;
    int column = 0;

    std::string toString() const;
};

// Distinct process exit codes so scripts and schedulers can tell failures apart.
enum class ExitCode : int {
    Ok = 0,
    Internal = 1,
    Usage = 2,
    Config = 3,
    Scene = 4,
    Output = 5,
    Render = 6,
    Interrupted = 130,
};

// The one error type: a message, an optional location and the exit code it maps to.
class Error : public std::runtime_error {
public:
    Error(ExitCode code, std::string message, FileLoc loc = {});

    ExitCode code() const { return code_; }
    const FileLoc& loc() const { return loc_; }
    const std::string& message() const { return message_; }

private:
    ExitCode code_;
    FileLoc loc_;
    std::string message_;
};

[[noreturn]] void throwConfigError(const FileLoc& loc, std::string_view message);
[[noreturn]] void throwSceneError(const FileLoc& loc, std::string_view message);

}  // namespace clipblur
