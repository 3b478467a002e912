#pragma once

#include <string>

#include "io/config/config_node.h"

namespace clipblur::config {

// Parses YAML text (file names the source for locations) into the document tree. Nesting depth is
// bounded by a pre-scan before yaml-cpp sees the text, since yaml-cpp recurses once per level.
ConfigNode readYaml(const std::string& text, const std::string& file);

// Conservative upper bound of the nesting depth of YAML text, and where it is reached; exposed for tests.
struct YamlDepth {
    int depth = 0;
    std::size_t first_over_limit = std::string::npos;  // offset where kMaxNestingDepth is first exceeded
};
YamlDepth estimateYamlDepth(const std::string& text);

}  // namespace clipblur::config
