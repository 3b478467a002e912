#include "io/config/overrides.h"

#include <vector>

#include "io/config/scalar.h"
#include "io/config/yaml_reader.h"

namespace clipblur::config {

namespace {

const std::string kSetFile = "<--set>";

FileLoc setLoc(std::size_t offset) { return FileLoc{kSetFile, 1, static_cast<int>(offset) + 1}; }

void shiftColumns(ConfigNode& node, int by) {
    if (node.loc.line == 1) node.loc.column += by;
    for (ConfigNode& item : node.items) shiftColumns(item, by);
    for (ConfigNode::Entry& e : node.entries) {
        if (e.key_loc.line == 1) e.key_loc.column += by;
        shiftColumns(e.value, by);
    }
}

struct Segment {
    std::string name;
    std::size_t offset;
};

}  // namespace

void applyOverride(ConfigNode& root, const std::string& assignment) {
    const std::size_t eq = assignment.find('=');
    if (eq == std::string::npos)
        throwConfigError(setLoc(0), "override '" + assignment + "' is not of the form key.path=value");
    if (assignment.find('\n') != std::string::npos)
        throwConfigError(setLoc(assignment.find('\n')), "override must be a single line");

    std::vector<Segment> path;
    std::size_t start = 0;
    while (true) {
        const std::size_t dot = assignment.find('.', start);
        const std::size_t end = dot == std::string::npos || dot > eq ? eq : dot;
        if (end == start) throwConfigError(setLoc(start), "empty key in override path");
        path.push_back(Segment{assignment.substr(start, end - start), start});
        if (end == eq) break;
        start = end + 1;
    }

    if (assignment.find_first_not_of(" \t", eq + 1) == std::string::npos)
        throwConfigError(setLoc(eq), "override '" + assignment + "' has no value after '='");
    ConfigNode value;
    try {
        value = readYaml(assignment.substr(eq + 1), kSetFile);
    } catch (const Error& e) {
        FileLoc loc = e.loc();
        if (loc.line == 1) loc.column += static_cast<int>(eq + 1);
        throw Error(e.code(), e.message(), loc);
    }
    // yaml-cpp columns count from the value's start; a value it leaves unlocated starts there.
    shiftColumns(value, static_cast<int>(eq + 1));
    if (value.loc.line == 0) value.loc = setLoc(eq + 1);

    if (!root.isMap()) throwConfigError(root.loc, "the document must be a map to apply overrides");
    ConfigNode* node = &root;
    std::string walked;
    for (std::size_t i = 0; i < path.size(); ++i) {
        const Segment& seg = path[i];
        const bool last = i + 1 == path.size();
        const FileLoc seg_loc = setLoc(seg.offset);
        ConfigNode* child = nullptr;
        if (node->isSequence()) {
            const auto index = parseUnsigned(seg.name);
            if (!index)
                throwConfigError(seg_loc, "'" + walked + "' is a list; '" + seg.name + "' is not an index");
            if (*index >= node->items.size())
                throwConfigError(seg_loc, "index " + seg.name + " is out of range: '" + walked + "' has " +
                                              std::to_string(node->items.size()) + " items");
            child = &node->items[*index];
        } else if (node->isMap()) {
            child = node->find(seg.name);
            if (!child) {
                ConfigNode fresh = last ? ConfigNode::makeNull(seg_loc) : ConfigNode::makeMap(seg_loc);
                child = &node->insert(seg.name, seg_loc, std::move(fresh));
            }
        } else {
            throwConfigError(seg_loc, "cannot set '" + seg.name + "': '" + walked + "' is a " +
                                          kindName(node->kind) + ", not a map or list");
        }
        walked += (walked.empty() ? "" : ".") + seg.name;
        node = child;
    }
    *node = std::move(value);
}

}  // namespace clipblur::config
