#include <string>

#include <gtest/gtest.h>

#include "io/config/config_node.h"
#include "io/config/document_reader.h"
#include "io/config/json_reader.h"
#include "io/config/yaml_reader.h"
#include "tests/io/config/config_test_util.h"

namespace clipblur::config {

using clipblur::testing::catchError;

static void expectLoc(const FileLoc& loc, const std::string& file, int line, int column) {
    EXPECT_EQ(loc.file, file);
    EXPECT_EQ(loc.line, line);
    EXPECT_EQ(loc.column, column);
}

TEST(YamlReader, LocationsAreOneBased) {
    const ConfigNode doc = readYaml("version: 1\nfilm:\n  width: 320\n  background: [1, 2, 3]\n", "a.yaml");
    ASSERT_TRUE(doc.isMap());
    ASSERT_EQ(doc.entries.size(), 2u);
    expectLoc(doc.entries[1].key_loc, "a.yaml", 2, 1);
    const ConfigNode* film = doc.find("film");
    ASSERT_NE(film, nullptr);
    expectLoc(film->find("width")->loc, "a.yaml", 3, 10);
    expectLoc(film->find("background")->items[2].loc, "a.yaml", 4, 22);
    EXPECT_EQ(film->find("width")->scalar, "320");
}

TEST(YamlReader, QuotedScalarsAreStrings) {
    const ConfigNode doc = readYaml("a: 5\nb: \"5\"\nc: '5'\n", "a.yaml");
    EXPECT_EQ(doc.find("a")->style, ConfigNode::Style::Plain);
    EXPECT_EQ(doc.find("b")->style, ConfigNode::Style::Quoted);
    EXPECT_EQ(doc.find("c")->style, ConfigNode::Style::Quoted);
}

TEST(YamlReader, DuplicateKeyIsLocated) {
    const Error e = catchError([] { readYaml("version: 1\nfilm: {}\nversion: 2\n", "d.yaml"); });
    EXPECT_EQ(e.code(), ExitCode::Config);
    expectLoc(e.loc(), "d.yaml", 3, 1);
    EXPECT_NE(e.message().find("duplicate key 'version'"), std::string::npos);
}

TEST(YamlReader, SyntaxErrorIsLocated) {
    // The unterminated flow sequence is detected at the end of the text, line 3.
    const Error e = catchError([] { readYaml("version: 1\nfilm: [1, 2\nother: 3\n", "s.yaml"); });
    EXPECT_EQ(e.code(), ExitCode::Config);
    EXPECT_EQ(e.loc().file, "s.yaml");
    EXPECT_GE(e.loc().line, 2);
}

TEST(YamlReader, DeepFlowNestingIsRefusedBeforeParsing) {
    const std::string text = "a: " + std::string(100000, '[');
    const Error e = catchError([&] { readYaml(text, "deep.yaml"); });
    EXPECT_EQ(e.code(), ExitCode::Config);
    // Depth 1 is the top-level map; bracket k (1-based, column 3 + k) opens level 1 + k, so level 65
    // is reached by bracket 64 at column 67.
    expectLoc(e.loc(), "deep.yaml", 1, 67);
}

TEST(YamlReader, DeepBlockNestingIsRefusedBeforeParsing) {
    std::string text;
    // 2000 levels (text grows quadratically with block depth); the 100000-level case is the dashes.
    for (int i = 0; i < 2000; ++i) text += std::string(static_cast<std::size_t>(i), ' ') + "k:\n";
    const Error e = catchError([&] { readYaml(text, "deep.yaml"); });
    EXPECT_EQ(e.code(), ExitCode::Config);
    expectLoc(e.loc(), "deep.yaml", 65, 65);

    const std::string dashes = [] {
        std::string s;
        for (int i = 0; i < 100000; ++i) s += "- ";
        return s + "x\n";
    }();
    EXPECT_EQ(catchError([&] { readYaml(dashes, "dash.yaml"); }).code(), ExitCode::Config);
}

TEST(YamlReader, ModerateNestingIsAccepted) {
    std::string text;
    for (int i = 0; i < 20; ++i) text += std::string(static_cast<std::size_t>(2 * i), ' ') + "k:\n";
    EXPECT_NO_THROW(readYaml(text, "ok.yaml"));
    EXPECT_NO_THROW(readYaml("a: " + std::string(30, '[') + std::string(30, ']') + "\n", "ok.yaml"));
}

TEST(YamlReader, AliasExpansionIsBounded) {
    // Each level multiplies by ten: 10^8 nodes if expanded, far above kMaxDocumentNodes.
    std::string text = "l0: &l0 [0, 0, 0, 0, 0, 0, 0, 0, 0, 0]\n";
    for (int i = 1; i < 8; ++i) {
        text += "l" + std::to_string(i) + ": &l" + std::to_string(i) + " [";
        for (int k = 0; k < 10; ++k) text += std::string(k ? ", " : "") + "*l" + std::to_string(i - 1);
        text += "]\n";
    }
    const Error e = catchError([&] { readYaml(text, "bomb.yaml"); });
    EXPECT_EQ(e.code(), ExitCode::Config);
    EXPECT_NE(e.message().find("alias"), std::string::npos);
}

TEST(JsonReader, LocationsOfKeysAndValues) {
    const std::string text = "{\n  \"version\": 1,\n  \"film\": {\"width\": 320, \"bg\": [0.5, \"x\"]}\n}\n";
    const ConfigNode doc = readJson(text, "a.json");
    expectLoc(doc.loc, "a.json", 1, 1);
    expectLoc(doc.entries[0].key_loc, "a.json", 2, 3);
    expectLoc(doc.entries[0].value.loc, "a.json", 2, 14);
    expectLoc(doc.entries[1].key_loc, "a.json", 3, 3);
    const ConfigNode* film = doc.find("film");
    expectLoc(film->loc, "a.json", 3, 11);
    expectLoc(film->entries[0].key_loc, "a.json", 3, 12);
    expectLoc(film->find("width")->loc, "a.json", 3, 21);
    expectLoc(film->find("bg")->loc, "a.json", 3, 32);
    expectLoc(film->find("bg")->items[1].loc, "a.json", 3, 38);
    EXPECT_EQ(film->find("bg")->items[0].scalar, "0.5");
    EXPECT_EQ(film->find("bg")->items[1].style, ConfigNode::Style::Quoted);
}

TEST(JsonReader, EscapedStringsDoNotConfuseLocations) {
    const std::string text = "{\"a\": \"q\\\"[{,:\", \"b\": 2}";
    const ConfigNode doc = readJson(text, "e.json");
    EXPECT_EQ(doc.find("a")->scalar, "q\"[{,:");
    expectLoc(doc.find("b")->loc, "e.json", 1, 23);
}

TEST(JsonReader, SyntaxErrorIsLocated) {
    const Error e = catchError([] { readJson("{\n  \"a\": 1,,\n}\n", "s.json"); });
    EXPECT_EQ(e.code(), ExitCode::Config);
    expectLoc(e.loc(), "s.json", 2, 10);  // the second comma: 2 spaces, "a" (3), ':', ' ', '1', ','
    EXPECT_NE(e.message().find("JSON syntax error"), std::string::npos);
}

TEST(JsonReader, DuplicateKeyIsLocated) {
    const Error e = catchError([] { readJson("{\"version\": 1,\n \"version\": 1}", "d.json"); });
    EXPECT_EQ(e.code(), ExitCode::Config);
    expectLoc(e.loc(), "d.json", 2, 2);
}

TEST(JsonReader, DeepNestingIsRefused) {
    const std::string text = std::string(100000, '[') + std::string(100000, ']');
    const Error e = catchError([&] { readJson(text, "deep.json"); });
    EXPECT_EQ(e.code(), ExitCode::Config);
    expectLoc(e.loc(), "deep.json", 1, 65);  // the 65th bracket opens level 65
}

TEST(DocumentReader, ExtensionChoosesFrontEnd) {
    EXPECT_TRUE(parseDocument("a: 1\n", "x.YML").isMap());
    EXPECT_TRUE(parseDocument("{\"a\": 1}", "x.json").isMap());
    EXPECT_EQ(catchError([] { parseDocument("a: 1", "x.toml"); }).code(), ExitCode::Config);
    EXPECT_EQ(catchError([] { parseDocument("a: 1", "x.json"); }).code(), ExitCode::Config);
}

TEST(DocumentReader, OversizedFileIsRefusedBeforeReading) {
    const auto dir = clipblur::testing::testDir();
    const auto path = dir / "big.yaml";
    {
        std::ofstream out(path, std::ios::binary);
        out << "a: 1\n";
        out.seekp(static_cast<std::streamoff>(kMaxDocumentBytes) + 1);
        out << '\n';
    }
    const Error e = catchError([&] { readDocument(path); });
    EXPECT_EQ(e.code(), ExitCode::Config);
    EXPECT_NE(e.message().find("larger than"), std::string::npos);
}

TEST(ConfigHash, SameForYamlAndJsonSpellings) {
    const ConfigNode y = readYaml("version: 1\nfilm: {width: 320, background: 0.50}\nname: auto\n", "a.yaml");
    const ConfigNode j = readJson("{\"name\": \"auto\", \"film\": {\"background\": 0.5, \"width\": 320.0}, \"version\": 1}",
                                  "a.json");
    EXPECT_EQ(canonicalText(y), canonicalText(j));
    EXPECT_EQ(configHash(y), configHash(j));
    EXPECT_EQ(configHash(y).size(), 16u);
    const ConfigNode changed = readYaml("version: 1\nfilm: {width: 321, background: 0.5}\nname: auto\n", "a.yaml");
    EXPECT_NE(configHash(y), configHash(changed));
    // A quoted number is a different document from a number.
    EXPECT_NE(configHash(readYaml("a: 5", "a.yaml")), configHash(readYaml("a: '5'", "a.yaml")));
}

TEST(ConfigHash, Fnv1a64MatchesPublishedVectors) {
    // Test vectors from the FNV reference (Fowler/Noll/Vo): "" and "a".
    EXPECT_EQ(fnv1a64Hex(""), "cbf29ce484222325");
    EXPECT_EQ(fnv1a64Hex("a"), "af63dc4c8601ec8c");
    EXPECT_EQ(fnv1a64Hex("foobar"), "85944171f73967e8");
    EXPECT_EQ(configHash(ConfigNode::makeNull({})), fnv1a64Hex("null"));
}

}  // namespace clipblur::config
