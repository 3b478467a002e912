#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "scene/error.h"

namespace clipblur::config {

// Caps applied while reading a document, before any schema check: they keep hostile input from
// exhausting the stack (both parser libraries recurse per nesting level) or memory.
inline constexpr std::size_t kMaxDocumentBytes = std::size_t{16} << 20;
inline constexpr int kMaxNestingDepth = 64;
inline constexpr std::size_t kMaxDocumentNodes = std::size_t{1} << 18;

// One node of the format-neutral document tree that both the YAML and the JSON front-end produce.
// Every node and every map key knows where it came from, so any later error can say file:line:col.
struct ConfigNode {
    enum class Kind { Null, Scalar, Sequence, Map };
    // Quoted scalars are strings even when they look like numbers ("5" is not 5).
    enum class Style { Plain, Quoted };

    struct Entry;

    Kind kind = Kind::Null;
    Style style = Style::Plain;
    FileLoc loc;
    std::string scalar;
    std::vector<ConfigNode> items;   // Sequence
    std::vector<Entry> entries;      // Map, in document order

    static ConfigNode makeNull(FileLoc loc);
    static ConfigNode makeScalar(std::string text, Style style, FileLoc loc);
    static ConfigNode makeSequence(FileLoc loc);
    static ConfigNode makeMap(FileLoc loc);

    bool isMap() const { return kind == Kind::Map; }
    bool isSequence() const { return kind == Kind::Sequence; }
    bool isScalar() const { return kind == Kind::Scalar; }
    bool isNull() const { return kind == Kind::Null; }

    const ConfigNode* find(const std::string& key) const;
    ConfigNode* find(const std::string& key);
    // Appends a key; a key already present is a config error at the new key's location.
    ConfigNode& insert(std::string key, FileLoc key_loc, ConfigNode value);
};

struct ConfigNode::Entry {
    std::string key;
    FileLoc key_loc;
    ConfigNode value;
};

const char* kindName(ConfigNode::Kind kind);

// A stable text form independent of the source format: map keys sorted, numbers in shortest
// round-trip form, strings quoted and escaped. YAML and JSON spellings of one job give one text.
std::string canonicalText(const ConfigNode& node);

// FNV-1a 64-bit of text as 16 lower-case hex digits, and of canonicalText(node).
std::string fnv1a64Hex(const std::string& text);
std::string configHash(const ConfigNode& node);

// 1-based line and column of a byte offset in text (columns count bytes).
FileLoc locationOfOffset(const std::string& file, const std::string& text, std::size_t offset);

}  // namespace clipblur::config
