#pragma once

#include <string>

#include "io/config/config_node.h"

namespace clipblur::config {

// Parses JSON text into the document tree with nlohmann's SAX interface. nlohmann reports no
// positions for values, so a small cursor walks the same text in step with the SAX events and
// records where each value and key token starts.
ConfigNode readJson(const std::string& text, const std::string& file);

}  // namespace clipblur::config
