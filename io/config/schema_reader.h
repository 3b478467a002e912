#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "io/config/config_node.h"

namespace clipblur::config {

// Whether a vector value may also be written as one number meaning all three components (colours).
enum class ScalarForm { Refused, Allowed };

// Typed, range-checked access to one map of the document. Every key read is marked consumed, and
// finish() rejects whatever was not: a key the schema does not know can never be silently ignored.
// `path` names the map in messages ("film", "objects[2].transform[0]").
class MapReader {
public:
    MapReader(const ConfigNode& node, std::string path);

    const FileLoc& loc() const { return node_.loc; }
    const std::string& path() const { return path_; }
    std::string keyPath(std::string_view key) const;

    bool has(std::string_view key) const;
    const ConfigNode* optional(std::string_view key);
    const ConfigNode& required(std::string_view key);

    double number(std::string_view key, double fallback, double lo, double hi);
    double requiredNumber(std::string_view key, double lo, double hi);
    int integer(std::string_view key, int fallback, int lo, int hi);
    bool boolean(std::string_view key, bool fallback);
    std::string string(std::string_view key, std::string fallback);
    // Three numbers, or one number repeated (a grey colour, a uniform scale).
    glm::dvec3 vec3(std::string_view key, glm::dvec3 fallback, double lo, double hi, ScalarForm scalar);

    // Errors, located at the first key not read, when any key is left over.
    void finish() const;

private:
    const ConfigNode& node_;
    std::string path_;
    std::vector<bool> used_;
};

// Conversions of single nodes; `what` names the value in messages.
double asNumber(const ConfigNode& node, const std::string& what, double lo, double hi);
std::int64_t asInteger(const ConfigNode& node, const std::string& what, std::int64_t lo, std::int64_t hi);
std::uint64_t asUnsigned(const ConfigNode& node, const std::string& what);
bool asBool(const ConfigNode& node, const std::string& what);
std::string asString(const ConfigNode& node, const std::string& what);
glm::dvec3 asVec3(const ConfigNode& node, const std::string& what, double lo, double hi, ScalarForm scalar);
const std::vector<ConfigNode>& asList(const ConfigNode& node, const std::string& what);

// Index of the node's string among `names`; errors list the accepted names.
int asChoice(const ConfigNode& node, const std::string& what, std::initializer_list<std::string_view> names);

}  // namespace clipblur::config
