#include "io/config/config_node.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>

#include "io/config/scalar.h"

namespace clipblur::config {

ConfigNode ConfigNode::makeNull(FileLoc loc) {
    ConfigNode n;
    n.kind = Kind::Null;
    n.loc = std::move(loc);
    return n;
}

ConfigNode ConfigNode::makeScalar(std::string text, Style style, FileLoc loc) {
    ConfigNode n;
    n.kind = Kind::Scalar;
    n.style = style;
    n.scalar = std::move(text);
    n.loc = std::move(loc);
    return n;
}

ConfigNode ConfigNode::makeSequence(FileLoc loc) {
    ConfigNode n;
    n.kind = Kind::Sequence;
    n.loc = std::move(loc);
    return n;
}

ConfigNode ConfigNode::makeMap(FileLoc loc) {
    ConfigNode n;
    n.kind = Kind::Map;
    n.loc = std::move(loc);
    return n;
}

const ConfigNode* ConfigNode::find(const std::string& key) const {
    for (const Entry& e : entries)
        if (e.key == key) return &e.value;
    return nullptr;
}

ConfigNode* ConfigNode::find(const std::string& key) {
    for (Entry& e : entries)
        if (e.key == key) return &e.value;
    return nullptr;
}

ConfigNode& ConfigNode::insert(std::string key, FileLoc key_loc, ConfigNode value) {
    for (const Entry& e : entries)
        if (e.key == key)
            throwConfigError(key_loc, "duplicate key '" + key + "' (first given at " + e.key_loc.toString() + ")");
    entries.push_back(Entry{std::move(key), std::move(key_loc), std::move(value)});
    return entries.back().value;
}

const char* kindName(ConfigNode::Kind kind) {
    switch (kind) {
        case ConfigNode::Kind::Null: return "null";
        case ConfigNode::Kind::Scalar: return "scalar";
        case ConfigNode::Kind::Sequence: return "list";
        case ConfigNode::Kind::Map: return "map";
    }
    return "?";
}

namespace {

void appendQuoted(std::string& out, const std::string& s) {
    out += '"';
    for (const unsigned char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += static_cast<char>(c);
        } else if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
        } else {
            out += static_cast<char>(c);
        }
    }
    out += '"';
}

void appendCanonical(std::string& out, const ConfigNode& node) {
    switch (node.kind) {
        case ConfigNode::Kind::Null: out += "null"; return;
        case ConfigNode::Kind::Scalar: {
            if (node.style == ConfigNode::Style::Plain) {
                if (const auto d = parseNumber(node.scalar)) {
                    char buf[64];
                    const auto r = std::to_chars(buf, buf + sizeof buf, *d);
                    out.append(buf, r.ptr);
                    return;
                }
                if (node.scalar == "true" || node.scalar == "false") {
                    out += node.scalar;
                    return;
                }
            }
            appendQuoted(out, node.scalar);
            return;
        }
        case ConfigNode::Kind::Sequence: {
            out += '[';
            for (std::size_t i = 0; i < node.items.size(); ++i) {
                if (i) out += ',';
                appendCanonical(out, node.items[i]);
            }
            out += ']';
            return;
        }
        case ConfigNode::Kind::Map: {
            std::vector<const ConfigNode::Entry*> sorted;
            sorted.reserve(node.entries.size());
            for (const auto& e : node.entries) sorted.push_back(&e);
            std::sort(sorted.begin(), sorted.end(), [](auto* a, auto* b) { return a->key < b->key; });
            out += '{';
            for (std::size_t i = 0; i < sorted.size(); ++i) {
                if (i) out += ',';
                appendQuoted(out, sorted[i]->key);
                out += ':';
                appendCanonical(out, sorted[i]->value);
            }
            out += '}';
            return;
        }
    }
}

}  // namespace

std::string canonicalText(const ConfigNode& node) {
    std::string out;
    appendCanonical(out, node);
    return out;
}

std::string configHash(const ConfigNode& node) { return fnv1a64Hex(canonicalText(node)); }

std::string fnv1a64Hex(const std::string& text) {
    std::uint64_t h = 0xcbf29ce484222325ull;
    for (const unsigned char c : text) {
        h ^= c;
        h *= 0x100000001b3ull;
    }
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
    return buf;
}

FileLoc locationOfOffset(const std::string& file, const std::string& text, std::size_t offset) {
    offset = std::min(offset, text.size());
    int line = 1;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < offset; ++i) {
        if (text[i] == '\n') {
            ++line;
            line_start = i + 1;
        }
    }
    return FileLoc{file, line, static_cast<int>(offset - line_start) + 1};
}

}  // namespace clipblur::config
