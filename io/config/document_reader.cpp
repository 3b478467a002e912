#include "io/config/document_reader.h"

#include <fstream>
#include <iterator>
#include <system_error>

#include "io/config/json_reader.h"
#include "io/config/yaml_reader.h"

namespace clipblur::config {

ConfigNode parseDocument(const std::string& text, const std::string& file_name) {
    std::string ext = std::filesystem::path(file_name).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (ext == ".yaml" || ext == ".yml") return readYaml(text, file_name);
    if (ext == ".json") return readJson(text, file_name);
    throwConfigError(FileLoc{file_name, 0, 0}, "unknown job file extension '" + ext + "' (expected .yaml, .yml or .json)");
}

ConfigNode readDocument(const std::filesystem::path& file) {
    const std::string name = file.string();
    std::error_code ec;
    const auto size = std::filesystem::file_size(file, ec);
    if (ec) throwConfigError(FileLoc{name, 0, 0}, "cannot read job file: " + ec.message());
    if (size > kMaxDocumentBytes)
        throwConfigError(FileLoc{name, 0, 0}, "file is larger than " + std::to_string(kMaxDocumentBytes >> 20) + " MiB");
    std::ifstream in(file, std::ios::binary);
    if (!in) throwConfigError(FileLoc{name, 0, 0}, "cannot open job file");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throwConfigError(FileLoc{name, 0, 0}, "error while reading job file");
    return parseDocument(text, name);
}

}  // namespace clipblur::config
