#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scene/job.h"

namespace clipblur {

// Reads a render job (YAML or JSON, one schema), applies `overrides` ("key.path=value", as given to
// --set) before validation, builds the scene (primitives expanded to meshes, OBJ files loaded) and
// validates it. Throws clipblur::Error with file:line:col on any problem. `read_files`, when given,
// receives every file read: the job file, then the OBJ files (meshes and deformation keys), then the
// glTF scene file and its external buffers.
RenderJob loadJob(const std::filesystem::path& file, const std::vector<std::string>& overrides = {},
                  std::vector<std::filesystem::path>* read_files = nullptr);

// The same from text in memory: `file_name` picks the front-end by its extension, names the source
// in messages and anchors relative OBJ paths. Used by the fuzzer and by tests.
RenderJob loadJobFromText(const std::string& text, const std::filesystem::path& file_name,
                          const std::vector<std::string>& overrides = {});

}  // namespace clipblur
