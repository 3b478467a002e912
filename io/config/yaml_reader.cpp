#include "io/config/yaml_reader.h"

#include <algorithm>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace clipblur::config {

namespace {

bool isSpace(char c) { return c == ' ' || c == '\t'; }

// True when a line's content (after indentation and "- " prefixes) opens a block scalar (| or >),
// whose more-indented body lines are text, not structure.
bool opensBlockScalar(const std::string& text, std::size_t begin, std::size_t end) {
    while (end > begin && (isSpace(text[end - 1]) || text[end - 1] == '\r')) --end;
    while (end > begin && (text[end - 1] == '+' || text[end - 1] == '-' ||
                           (text[end - 1] >= '0' && text[end - 1] <= '9')))
        --end;
    return end > begin && (text[end - 1] == '|' || text[end - 1] == '>');
}

void note(YamlDepth& d, int depth, std::size_t offset) {
    d.depth = std::max(d.depth, depth);
    if (depth > kMaxNestingDepth && d.first_over_limit == std::string::npos) d.first_over_limit = offset;
}

}  // namespace

// Block depth is bounded by the number of distinct open indentation levels plus the "- " entries
// that open on one line; flow depth by unclosed brackets outside quotes and comments. Each may
// count a level twice (a "- key:" line), which is harmless for a cap far above real jobs.
YamlDepth estimateYamlDepth(const std::string& text) {
    YamlDepth worst;
    std::vector<std::size_t> indents;
    int flow = 0;
    std::size_t block_scalar_indent = std::string::npos;
    std::size_t pos = 0;
    while (pos < text.size()) {
        std::size_t eol = text.find('\n', pos);
        if (eol == std::string::npos) eol = text.size();
        std::size_t i = pos;
        while (i < eol && text[i] == ' ') ++i;
        const std::size_t indent = i - pos;
        const bool blank = i == eol || text[i] == '#' || text[i] == '\r';
        if (block_scalar_indent != std::string::npos) {
            if (blank || indent > block_scalar_indent) {
                pos = eol + 1;
                continue;
            }
            block_scalar_indent = std::string::npos;
        }
        if (blank) {
            pos = eol + 1;
            continue;
        }
        int line_depth = 0;
        if (flow == 0) {
            while (!indents.empty() && indents.back() > indent) indents.pop_back();
            if (indents.empty() || indents.back() != indent) indents.push_back(indent);
            line_depth = static_cast<int>(indents.size());
            std::size_t j = i;
            while (j + 1 < eol && (text[j] == '-' || text[j] == '?') && isSpace(text[j + 1])) {
                ++line_depth;
                j += 2;
                while (j < eol && isSpace(text[j])) ++j;
            }
            if (opensBlockScalar(text, j, eol)) block_scalar_indent = indent;
        }
        char quote = 0;
        for (std::size_t j = i; j < eol; ++j) {
            const char c = text[j];
            if (quote) {
                if (c == quote) quote = 0;
                else if (c == '\\' && quote == '"') ++j;
                continue;
            }
            if (c == '#' && (j == i || isSpace(text[j - 1]))) break;
            if (c == '"' || c == '\'') {
                if (j == i || isSpace(text[j - 1]) || text[j - 1] == '[' || text[j - 1] == '{' ||
                    text[j - 1] == ',' || text[j - 1] == ':')
                    quote = c;
            } else if (c == '[' || c == '{') {
                ++flow;
                note(worst, line_depth + flow, j);
            } else if ((c == ']' || c == '}') && flow > 0) {
                --flow;
            }
        }
        note(worst, line_depth + flow, i);
        pos = eol + 1;
    }
    return worst;
}

namespace {

class Converter {
public:
    explicit Converter(const std::string& file) : file_(file) {}

    ConfigNode convert(const YAML::Node& node, int depth) {
        const FileLoc loc = locOf(node.Mark());
        if (depth > kMaxNestingDepth)
            throwConfigError(loc, "nesting deeper than " + std::to_string(kMaxNestingDepth) + " levels");
        // Aliases share nodes, so a small file can expand exponentially; count what we build.
        if (++nodes_ > kMaxDocumentNodes)
            throwConfigError(loc, "document has more than " + std::to_string(kMaxDocumentNodes) +
                                      " values (after alias expansion)");
        switch (node.Type()) {
            case YAML::NodeType::Undefined:
            case YAML::NodeType::Null: return ConfigNode::makeNull(loc);
            case YAML::NodeType::Scalar:
                return ConfigNode::makeScalar(node.Scalar(),
                                              node.Tag() == "?" ? ConfigNode::Style::Plain
                                                                : ConfigNode::Style::Quoted,
                                              loc);
            case YAML::NodeType::Sequence: {
                ConfigNode seq = ConfigNode::makeSequence(loc);
                for (const YAML::Node& item : node) seq.items.push_back(convert(item, depth + 1));
                return seq;
            }
            case YAML::NodeType::Map: {
                ConfigNode map = ConfigNode::makeMap(loc);
                for (const auto& kv : node) {
                    const FileLoc key_loc = locOf(kv.first.Mark());
                    if (!kv.first.IsScalar()) throwConfigError(key_loc, "map keys must be plain names");
                    map.insert(kv.first.Scalar(), key_loc, convert(kv.second, depth + 1));
                }
                return map;
            }
        }
        return ConfigNode::makeNull(loc);
    }

private:
    FileLoc locOf(const YAML::Mark& mark) const {
        if (mark.is_null()) return FileLoc{file_, 0, 0};
        return FileLoc{file_, mark.line + 1, mark.column + 1};
    }

    const std::string& file_;
    std::size_t nodes_ = 0;
};

}  // namespace

ConfigNode readYaml(const std::string& text, const std::string& file) {
    if (text.size() > kMaxDocumentBytes)
        throwConfigError(FileLoc{file, 0, 0}, "file is larger than " + std::to_string(kMaxDocumentBytes >> 20) + " MiB");
    const YamlDepth depth = estimateYamlDepth(text);
    if (depth.first_over_limit != std::string::npos)
        throwConfigError(locationOfOffset(file, text, depth.first_over_limit),
                         "nesting deeper than " + std::to_string(kMaxNestingDepth) + " levels");
    YAML::Node root;
    try {
        root = YAML::Load(text);
    } catch (const YAML::Exception& e) {
        const FileLoc loc = e.mark.is_null() ? FileLoc{file, 0, 0}
                                             : FileLoc{file, e.mark.line + 1, e.mark.column + 1};
        throwConfigError(loc, "YAML syntax error: " + e.msg);
    }
    try {
        return Converter(file).convert(root, 0);
    } catch (const YAML::Exception& e) {
        const FileLoc loc = e.mark.is_null() ? FileLoc{file, 0, 0}
                                             : FileLoc{file, e.mark.line + 1, e.mark.column + 1};
        throwConfigError(loc, "YAML error: " + e.msg);
    }
}

}  // namespace clipblur::config
