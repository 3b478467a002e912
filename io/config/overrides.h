#pragma once

#include <string>

#include "io/config/config_node.h"

namespace clipblur::config {

// Applies one "--set" assignment "key.path=value" to the document. Path segments are map keys or,
// on lists, 0-based indices of existing items; missing map keys (and maps on the way) are created,
// so optional settings can be given on the command line. The value is parsed as a YAML scalar or
// flow value; its nodes are located at "<--set>:1:col" with col the column in the assignment.
void applyOverride(ConfigNode& root, const std::string& assignment);

}  // namespace clipblur::config
