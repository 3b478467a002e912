#include "io/config/json_reader.h"

#include <vector>

#include <nlohmann/json.hpp>

namespace clipblur::config {

namespace {

// Finds the start of each token that produces a SAX event ({, [, key, scalar). Valid up to the
// point nlohmann has lexed, because it sees the same bytes and nlohmann emits events in order.
class TokenCursor {
public:
    explicit TokenCursor(const std::string& text) : text_(text) {
        if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;
    }

    std::size_t next() {
        while (pos_ < text_.size()) {
            const char c = text_[pos_];
            if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == ',' || c == ':' || c == '}' || c == ']')
                ++pos_;
            else
                break;
        }
        const std::size_t start = pos_;
        if (pos_ >= text_.size()) return start;
        const char c = text_[pos_];
        if (c == '{' || c == '[') {
            ++pos_;
        } else if (c == '"') {
            ++pos_;
            while (pos_ < text_.size() && text_[pos_] != '"') pos_ += text_[pos_] == '\\' ? 2 : 1;
            ++pos_;
        } else {
            while (pos_ < text_.size()) {
                const char d = text_[pos_];
                if (d == ' ' || d == '\t' || d == '\n' || d == '\r' || d == ',' || d == ']' || d == '}' || d == ':')
                    break;
                ++pos_;
            }
        }
        return start;
    }

private:
    const std::string& text_;
    std::size_t pos_ = 0;
};

class TreeBuilder : public nlohmann::json_sax<nlohmann::json> {
public:
    TreeBuilder(const std::string& text, const std::string& file) : text_(text), file_(file), cursor_(text) {}

    bool null() override { return add(ConfigNode::makeNull(here())); }
    bool boolean(bool v) override {
        return add(ConfigNode::makeScalar(v ? "true" : "false", ConfigNode::Style::Plain, here()));
    }
    bool number_integer(number_integer_t v) override {
        return add(ConfigNode::makeScalar(std::to_string(v), ConfigNode::Style::Plain, here()));
    }
    bool number_unsigned(number_unsigned_t v) override {
        return add(ConfigNode::makeScalar(std::to_string(v), ConfigNode::Style::Plain, here()));
    }
    bool number_float(number_float_t, const string_t& s) override {
        return add(ConfigNode::makeScalar(s, ConfigNode::Style::Plain, here()));
    }
    bool string(string_t& s) override {
        return add(ConfigNode::makeScalar(s, ConfigNode::Style::Quoted, here()));
    }
    bool binary(binary_t&) override { return add(ConfigNode::makeNull(here())); }

    bool start_object(std::size_t) override { return open(ConfigNode::makeMap(here())); }
    bool end_object() override { return close(); }
    bool start_array(std::size_t) override { return open(ConfigNode::makeSequence(here())); }
    bool end_array() override { return close(); }

    bool key(string_t& k) override {
        Frame& top = stack_.back();
        top.key = k;
        top.key_loc = here();
        return true;
    }

    bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& ex) override {
        // position counts the bytes read, including the offending one.
        const std::size_t offset = position > 0 ? position - 1 : 0;
        std::string what = ex.what();
        const std::size_t col = what.find("column ");
        const std::size_t colon = col == std::string::npos ? col : what.find(": ", col);
        if (colon != std::string::npos) what = what.substr(colon + 2);
        throwConfigError(locationOfOffset(file_, text_, offset), "JSON syntax error: " + what);
    }

    ConfigNode take() { return std::move(root_); }

private:
    struct Frame {
        ConfigNode node;
        std::string key;
        FileLoc key_loc;
    };

    // Offsets only grow, so lines are counted incrementally (locationOfOffset per token is quadratic).
    FileLoc here() {
        const std::size_t offset = cursor_.next();
        for (; scanned_ < offset && scanned_ < text_.size(); ++scanned_) {
            if (text_[scanned_] == '\n') {
                ++line_;
                line_start_ = scanned_ + 1;
            }
        }
        return FileLoc{file_, line_, static_cast<int>(offset - line_start_) + 1};
    }

    void count(const FileLoc& loc) {
        if (++nodes_ > kMaxDocumentNodes)
            throwConfigError(loc, "document has more than " + std::to_string(kMaxDocumentNodes) + " values");
    }

    bool add(ConfigNode node) {
        count(node.loc);
        if (stack_.empty()) {
            root_ = std::move(node);
            return true;
        }
        Frame& top = stack_.back();
        if (top.node.isMap())
            top.node.insert(std::move(top.key), top.key_loc, std::move(node));
        else
            top.node.items.push_back(std::move(node));
        return true;
    }

    bool open(ConfigNode node) {
        // nlohmann's parser is iterative, so the cap protects our own recursion over the tree.
        if (static_cast<int>(stack_.size()) >= kMaxNestingDepth)
            throwConfigError(node.loc, "nesting deeper than " + std::to_string(kMaxNestingDepth) + " levels");
        count(node.loc);
        stack_.push_back(Frame{std::move(node), {}, {}});
        return true;
    }

    bool close() {
        Frame done = std::move(stack_.back());
        stack_.pop_back();
        --nodes_;  // counted in open()
        return add(std::move(done.node));
    }

    const std::string& text_;
    const std::string& file_;
    TokenCursor cursor_;
    std::vector<Frame> stack_;
    ConfigNode root_;
    std::size_t nodes_ = 0;
    std::size_t scanned_ = 0;
    std::size_t line_start_ = 0;
    int line_ = 1;
};

}  // namespace

ConfigNode readJson(const std::string& text, const std::string& file) {
    if (text.size() > kMaxDocumentBytes)
        throwConfigError(FileLoc{file, 0, 0}, "file is larger than " + std::to_string(kMaxDocumentBytes >> 20) + " MiB");
    TreeBuilder builder(text, file);
    nlohmann::json::sax_parse(text.begin(), text.end(), &builder);
    return builder.take();
}

}  // namespace clipblur::config
