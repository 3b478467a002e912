#pragma once

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "scene/error.h"

namespace clipblur::testing {

// A fresh directory per test under gtest's temp dir, so tests can write job and OBJ files.
inline std::filesystem::path testDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    auto dir = std::filesystem::path(::testing::TempDir()) / "clipblur_config" /
               (std::string(info->test_suite_name()) + "." + info->name());
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

inline std::filesystem::path writeFile(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

// Runs f, which must throw clipblur::Error; returns it for checks on code, location and message.
template <typename F>
Error catchError(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e;
    }
    ADD_FAILURE() << "expected clipblur::Error";
    return Error(ExitCode::Ok, "no error");
}

}  // namespace clipblur::testing
