#include <gtest/gtest.h>

#include "io/config/overrides.h"
#include "io/config/yaml_reader.h"
#include "tests/io/config/config_test_util.h"

namespace clipblur::config {

using clipblur::testing::catchError;

namespace {

ConfigNode baseDoc() {
    return readYaml("version: 1\nrender: {samples: 4}\nobjects:\n  - name: a\n  - name: b\n", "job.yaml");
}

}  // namespace

TEST(Overrides, ReplacesScalarAndLocatesIt) {
    ConfigNode doc = baseDoc();
    applyOverride(doc, "render.samples=64");
    const ConfigNode* s = doc.find("render")->find("samples");
    EXPECT_EQ(s->scalar, "64");
    EXPECT_EQ(s->loc.file, "<--set>");
    EXPECT_EQ(s->loc.line, 1);
    EXPECT_EQ(s->loc.column, 16);  // first character after '='
}

TEST(Overrides, CreatesMissingMapsAndKeys) {
    ConfigNode doc = baseDoc();
    applyOverride(doc, "film.width=320");
    ASSERT_NE(doc.find("film"), nullptr);
    EXPECT_EQ(doc.find("film")->find("width")->scalar, "320");
}

TEST(Overrides, ListIndexAndFlowValue) {
    ConfigNode doc = baseDoc();
    applyOverride(doc, "objects.1.name='x y'");
    EXPECT_EQ(doc.find("objects")->items[1].find("name")->scalar, "x y");
    EXPECT_EQ(doc.find("objects")->items[1].find("name")->style, ConfigNode::Style::Quoted);
    applyOverride(doc, "film.background=[1, 0.5, 0]");
    const ConfigNode* bg = doc.find("film")->find("background");
    ASSERT_TRUE(bg->isSequence());
    ASSERT_EQ(bg->items.size(), 3u);
    EXPECT_EQ(bg->items[1].scalar, "0.5");
    EXPECT_EQ(bg->items[1].loc.column, 21);  // "film.background=[1, " is 20 characters
}

TEST(Overrides, BadPathsAreLocated) {
    ConfigNode doc = baseDoc();
    Error e = catchError([&] { applyOverride(doc, "objects.x.name=a"); });
    EXPECT_EQ(e.code(), ExitCode::Config);
    EXPECT_EQ(e.loc().toString(), "<--set>:1:9");
    e = catchError([&] { applyOverride(doc, "objects.7.name=a"); });
    EXPECT_EQ(e.loc().toString(), "<--set>:1:9");
    EXPECT_NE(e.message().find("out of range"), std::string::npos);
    e = catchError([&] { applyOverride(doc, "version.major=1"); });
    EXPECT_EQ(e.loc().toString(), "<--set>:1:9");
    e = catchError([&] { applyOverride(doc, "render..samples=1"); });
    EXPECT_EQ(e.loc().toString(), "<--set>:1:8");
    e = catchError([&] { applyOverride(doc, "render.samples"); });
    EXPECT_EQ(e.code(), ExitCode::Config);
    e = catchError([&] { applyOverride(doc, "=3"); });
    EXPECT_EQ(e.loc().toString(), "<--set>:1:1");
}

// Issue 24, kind 6: an empty value was reported at a column past the end of the argument.
TEST(Overrides, EmptyValueIsLocatedAtItsEqualsSign) {
    for (const std::string assignment : {"render.samples=", "film.width=", "objects.1.name=  ", "a="}) {
        SCOPED_TRACE(assignment);
        ConfigNode doc = baseDoc();
        const Error e = catchError([&] { applyOverride(doc, assignment); });
        EXPECT_EQ(e.code(), ExitCode::Config);
        EXPECT_EQ(e.loc().column, static_cast<int>(assignment.find('=')) + 1);
        EXPECT_LE(e.loc().column, static_cast<int>(assignment.size()));
        EXPECT_NE(e.message().find("has no value"), std::string::npos) << e.what();
    }
}

// Every node of a value lies inside the argument, at its own first character.
TEST(Overrides, ValueColumnsStayInsideTheArgument) {
    ConfigNode doc = baseDoc();
    applyOverride(doc, "render.samples=null");
    EXPECT_EQ(doc.find("render")->find("samples")->loc.column, 16);
    applyOverride(doc, "film.background=[1, 0.5, 0]");
    const ConfigNode* bg = doc.find("film")->find("background");
    EXPECT_EQ(bg->loc.column, 17);
    ASSERT_EQ(bg->items.size(), 3u);
    EXPECT_EQ(bg->items[1].loc.column, 21);
    applyOverride(doc, "render.samples=''");
    EXPECT_EQ(doc.find("render")->find("samples")->loc.column, 16);
}

TEST(Overrides, BadValueSyntaxIsLocated) {
    ConfigNode doc = baseDoc();
    const Error e = catchError([&] { applyOverride(doc, "render.samples=[1, 2"); });
    EXPECT_EQ(e.code(), ExitCode::Config);
    EXPECT_EQ(e.loc().file, "<--set>");
}

}  // namespace clipblur::config
