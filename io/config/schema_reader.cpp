#include "io/config/schema_reader.h"

#include <cmath>
#include <sstream>

#include "io/config/scalar.h"

namespace clipblur::config {

namespace {

std::string formatNumber(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::string describe(const ConfigNode& node) {
    if (node.isScalar()) return (node.style == ConfigNode::Style::Quoted ? "string '" : "'") + node.scalar + "'";
    return kindName(node.kind);
}

}  // namespace

MapReader::MapReader(const ConfigNode& node, std::string path) : node_(node), path_(std::move(path)) {
    if (!node.isMap())
        throwConfigError(node.loc, (path_.empty() ? std::string("the document") : "'" + path_ + "'") +
                                       " must be a map, got " + describe(node));
    used_.assign(node.entries.size(), false);
}

std::string MapReader::keyPath(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

bool MapReader::has(std::string_view key) const {
    for (const auto& e : node_.entries)
        if (e.key == key) return true;
    return false;
}

const ConfigNode* MapReader::optional(std::string_view key) {
    for (std::size_t i = 0; i < node_.entries.size(); ++i) {
        if (node_.entries[i].key == key) {
            used_[i] = true;
            return &node_.entries[i].value;
        }
    }
    return nullptr;
}

const ConfigNode& MapReader::required(std::string_view key) {
    if (const ConfigNode* n = optional(key)) return *n;
    throwConfigError(node_.loc, "missing required key '" + keyPath(key) + "'");
}

double MapReader::number(std::string_view key, double fallback, double lo, double hi) {
    const ConfigNode* n = optional(key);
    return n ? asNumber(*n, keyPath(key), lo, hi) : fallback;
}

double MapReader::requiredNumber(std::string_view key, double lo, double hi) {
    return asNumber(required(key), keyPath(key), lo, hi);
}

int MapReader::integer(std::string_view key, int fallback, int lo, int hi) {
    const ConfigNode* n = optional(key);
    return n ? static_cast<int>(asInteger(*n, keyPath(key), lo, hi)) : fallback;
}

bool MapReader::boolean(std::string_view key, bool fallback) {
    const ConfigNode* n = optional(key);
    return n ? asBool(*n, keyPath(key)) : fallback;
}

std::string MapReader::string(std::string_view key, std::string fallback) {
    const ConfigNode* n = optional(key);
    return n ? asString(*n, keyPath(key)) : fallback;
}

glm::dvec3 MapReader::vec3(std::string_view key, glm::dvec3 fallback, double lo, double hi, ScalarForm scalar) {
    const ConfigNode* n = optional(key);
    return n ? asVec3(*n, keyPath(key), lo, hi, scalar) : fallback;
}

void MapReader::finish() const {
    for (std::size_t i = 0; i < used_.size(); ++i)
        if (!used_[i])
            throwConfigError(node_.entries[i].key_loc, "unknown key '" + keyPath(node_.entries[i].key) + "'");
}

double asNumber(const ConfigNode& node, const std::string& what, double lo, double hi) {
    if (!node.isScalar() || node.style != ConfigNode::Style::Plain)
        throwConfigError(node.loc, "'" + what + "' must be a number, got " + describe(node));
    const auto v = parseNumber(node.scalar);
    if (!v) throwConfigError(node.loc, "'" + what + "' must be a finite number, got " + describe(node));
    if (!(*v >= lo && *v <= hi))
        throwConfigError(node.loc, "'" + what + "' must be in [" + formatNumber(lo) + ", " + formatNumber(hi) +
                                       "], got " + node.scalar);
    return *v;
}

std::int64_t asInteger(const ConfigNode& node, const std::string& what, std::int64_t lo, std::int64_t hi) {
    if (!node.isScalar() || node.style != ConfigNode::Style::Plain)
        throwConfigError(node.loc, "'" + what + "' must be an integer, got " + describe(node));
    const auto v = parseInteger(node.scalar);
    if (!v) throwConfigError(node.loc, "'" + what + "' must be an integer, got " + describe(node));
    if (*v < lo || *v > hi)
        throwConfigError(node.loc, "'" + what + "' must be in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                                       "], got " + node.scalar);
    return *v;
}

std::uint64_t asUnsigned(const ConfigNode& node, const std::string& what) {
    if (!node.isScalar() || node.style != ConfigNode::Style::Plain)
        throwConfigError(node.loc, "'" + what + "' must be a non-negative integer, got " + describe(node));
    const auto v = parseUnsigned(node.scalar);
    if (!v) throwConfigError(node.loc, "'" + what + "' must be a non-negative 64-bit integer, got " + describe(node));
    return *v;
}

bool asBool(const ConfigNode& node, const std::string& what) {
    const auto v = node.isScalar() && node.style == ConfigNode::Style::Plain ? parseBool(node.scalar) : std::nullopt;
    if (!v) throwConfigError(node.loc, "'" + what + "' must be true or false, got " + describe(node));
    return *v;
}

std::string asString(const ConfigNode& node, const std::string& what) {
    if (!node.isScalar()) throwConfigError(node.loc, "'" + what + "' must be a string, got " + describe(node));
    return node.scalar;
}

glm::dvec3 asVec3(const ConfigNode& node, const std::string& what, double lo, double hi, ScalarForm scalar) {
    const bool allow_scalar = scalar == ScalarForm::Allowed;
    if (allow_scalar && node.isScalar()) return glm::dvec3(asNumber(node, what, lo, hi));
    if (!node.isSequence() || node.items.size() != 3)
        throwConfigError(node.loc, "'" + what + "' must be a list of 3 numbers" +
                                       (allow_scalar ? std::string(" or one number") : std::string()) + ", got " +
                                       (node.isSequence() ? std::to_string(node.items.size()) + " items" : describe(node)));
    glm::dvec3 v;
    for (int i = 0; i < 3; ++i) v[i] = asNumber(node.items[i], what + "[" + std::to_string(i) + "]", lo, hi);
    return v;
}

const std::vector<ConfigNode>& asList(const ConfigNode& node, const std::string& what) {
    if (!node.isSequence()) throwConfigError(node.loc, "'" + what + "' must be a list, got " + describe(node));
    return node.items;
}

int asChoice(const ConfigNode& node, const std::string& what, std::initializer_list<std::string_view> names) {
    const std::string s = asString(node, what);
    int i = 0;
    std::string list;
    for (std::string_view n : names) {
        if (s == n) return i;
        list += (i ? ", " : "") + std::string(n);
        ++i;
    }
    throwConfigError(node.loc, "'" + what + "' must be one of " + list + ", got '" + s + "'");
}

}  // namespace clipblur::config
