#pragma once

#include <filesystem>
#include <string>

#include "io/config/config_node.h"

namespace clipblur::config {

// The front-end is chosen by the file name's extension: .yaml/.yml or .json.
ConfigNode parseDocument(const std::string& text, const std::string& file_name);

// Reads a file (refusing files over kMaxDocumentBytes before reading them) and parses it.
ConfigNode readDocument(const std::filesystem::path& file);

}  // namespace clipblur::config
