// A scene's [[bodies]] tables parsed a section at a time (io/body_sections.hpp) give the Scene, and
// the messages, that the whole document's tree gives; texts the splitter cannot read plainly are
// parsed whole.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cstring>
#include <filesystem>

#include "../support/scene_files.hpp"
#include "io/scene_sections.hpp"
#include "tumble/io/scene.hpp"

namespace tumble {
namespace {

namespace fs = std::filesystem;
using scene::split_body_sections;

/// The Scene of `text` read from the tree of the whole document, as before sections.
Scene whole(const std::string& text, const fs::path& path) {
  return scene::read_scene(scene::parse_toml(text, scene::TomlFile{path.string()}), text, path);
}

/// What reading `text` gives: "ok" or the message.
std::string outcome(const std::function<Scene()>& read) {
  try {
    read();
    return "ok";
  } catch (const Error& e) {
    return e.what();
  }
}

bool same_bits(const double* a, const double* b, size_t n) {
  return std::memcmp(a, b, n * sizeof(double)) == 0;
}

void expect_same_scene(const Scene& a, const Scene& b) {
  ASSERT_EQ(a.model.bodies.size(), b.model.bodies.size());
  for (size_t i = 0; i < a.model.bodies.size(); ++i) {
    const RigidBody &x = a.model.bodies[i], &y = b.model.bodies[i];
    EXPECT_EQ(x.name(), y.name());
    EXPECT_EQ(x.mass(), y.mass()) << x.name();
    EXPECT_TRUE(same_bits(x.Lambda().data(), y.Lambda().data(), 3)) << x.name();
    EXPECT_TRUE(same_bits(x.U().data(), y.U().data(), 9)) << x.name();
    EXPECT_TRUE(same_bits(x.center_of_mass().data(), y.center_of_mass().data(), 3)) << x.name();
    const BodyState &s = a.initial.bodies[i], &t = b.initial.bodies[i];
    EXPECT_TRUE(same_bits(s.o.data(), t.o.data(), 3) &&
                same_bits(s.q.coeffs().data(), t.q.coeffs().data(), 4) &&
                same_bits(s.v.data(), t.v.data(), 3) && same_bits(s.omega_w.data(), t.omega_w.data(), 3))
        << x.name();
    EXPECT_EQ(*a.body_info[i].source, *b.body_info[i].source);
    EXPECT_EQ(a.body_info[i].display == nullptr, b.body_info[i].display == nullptr);
    if (a.body_info[i].display && b.body_info[i].display) {
      EXPECT_EQ(a.body_info[i].display->vertices, b.body_info[i].display->vertices);
    }
  }
  EXPECT_EQ(a.model.particles.size(), b.model.particles.size());
  EXPECT_EQ(a.model.forces.size(), b.model.forces.size());
  EXPECT_EQ(a.events.size(), b.events.size());
  EXPECT_EQ(a.warnings, b.warnings);
  EXPECT_EQ(a.input_files, b.input_files);
  EXPECT_EQ(a.settings.duration, b.settings.duration);
  EXPECT_EQ(a.settings.integrator, b.settings.integrator);
  EXPECT_EQ(a.text, b.text);
}

const std::string kHead = "[simulation]\nduration = 1.0\ntimestep = 1e-3\n[world]\ngravity = [0, 0, -9.81]\n";

/// A [[bodies]] table with sub-tables, arrays over several lines (lines that start with '[' inside a
/// value), comments holding headers: a box of density 1000, or (odd i) a mass with its inertia tensor.
std::string body(int i) {
  const std::string mass = i % 2
                               ? "mass = 2.0\ninertia = [\n  [0.1, 0.0, 0.0],\n  [0.0, 0.2, 0.0],  # [row]\n"
                                 "  [0.0, 0.0, 0.25],\n]\n"
                               : "density = 1000.0\n[bodies.shape]\ntype = \"box\"\nsize = [0.1, 0.2, 0.3]\n";
  return fmt::format(
      "[[bodies]]  # [[not a header]]\n"
      "name = \"b{}\"\n"
      "position = [\n  {}.5,  # x, [m]\n  0.0,\n  0.0\n]\n"
      "{}"
      "[ bodies . orientation ]\naxis = [0, 0, 1]\nangle = 0.{}\n",
      i, i, mass, i + 1);
}

TEST(BodySections, TheSectionsHoldTheBodiesAndTheRestKeepsItsLines) {
  std::string text = "title = \"a [[bodies]] in a string\" # and [[bodies]] in a comment\n" + kHead;
  for (int i = 0; i < 3; ++i) text += body(i);
  text += "[[forces]]\ntype = \"damping\"\nbody = \"b1\"\nangular = 0.1\n";
  text += body(3);
  const auto split = split_body_sections(text);
  ASSERT_TRUE(split);
  EXPECT_EQ(split->bodies, 4u);
  ASSERT_EQ(split->sections.size(), 2u);  // b0–b2, then b3 after [[forces]]
  EXPECT_EQ(split->sections[0].first_line, 7u);
  EXPECT_TRUE(split->sections[0].text.starts_with("[[bodies]]"));
  EXPECT_TRUE(split->sections[1].text.starts_with("[[bodies]]"));
  EXPECT_EQ(split->sections[1].text, body(3));
  // The rest has every line, those of the sections empty.
  EXPECT_EQ(std::count(split->rest.begin(), split->rest.end(), '\n'),
            std::count(text.begin(), text.end(), '\n'));
  EXPECT_EQ(split->rest.find("bodies."), std::string::npos);
  EXPECT_NE(split->rest.find("[[forces]]\ntype = \"damping\""), std::string::npos);
}

TEST(BodySections, ManyBodiesMakeSectionsOfAboutTheirSize) {
  std::string text = kHead;
  for (int i = 0; i < 600; ++i) text += body(i);
  const auto split = split_body_sections(text);
  ASSERT_TRUE(split);
  EXPECT_EQ(split->bodies, 600u);
  EXPECT_GT(split->sections.size(), 2u);
  for (const auto& s : split->sections) EXPECT_LT(s.text.size(), scene::kBodySectionBytes + 512);
}

TEST(BodySections, TextsNotPlainEnoughAreParsedWhole) {
  // Each is declined by the splitter (and parsed whole by toml++, which says what is wrong, if anything).
  for (const std::string& text : {
           kHead,                                                    // no [[bodies]]
           kHead + "note = \"\"\"\n[[bodies]]\n\"\"\"\n" + body(0),  // a multi-line string
           kHead + "note = '''x'''\n" + body(0),
           kHead + "[[\"bodies\"]]\nname = \"a\"\n",              // a quoted key
           kHead + "[bodies.shape]\ntype = \"box\"\n" + body(0),  // bodies.x outside a section
           kHead + "[bodies]\n" + body(0),
           kHead + body(0) + "x = [1, 2\n",  // an array never closed
           kHead + body(0) + "x = ]\n", kHead + body(0) + "name = \"unterminated\n",
           kHead + "x = \"a line end escaped \\\n" + body(0),  // "\" and a line end: no single-line string
       }) {
    EXPECT_FALSE(split_body_sections(text)) << text;
  }
}

TEST(BodySections, SectionsGiveTheSceneOfTheWholeTree) {
  const test::TempDir dir("body_sections");
  // The examples, and a scene of many bodies, forces and events naming them, across sections.
  std::vector<fs::path> scenes;
  for (const auto& e : fs::directory_iterator(fs::path(TUMBLE_SOURCE_DIR) / "examples")) {
    if (e.path().extension() == ".toml") scenes.push_back(e.path());
  }
  std::string many = kHead;
  for (int i = 0; i < 700; ++i) many += body(i);
  many +=
      "[[forces]]\ntype = \"damping\"\nbody = \"b650\"\nangular = 0.1\n"
      "[[events]]\nname = \"low\"\nbody = \"b3\"\ncolumn = \"pz\"\nvalue = -1.0\n";
  scenes.push_back(dir.write("many.toml", many));
  for (const fs::path& path : scenes) {
    const std::string text = test::read_text(path);
    SCOPED_TRACE(path.filename().string());
    const Scene a = load_scene(path);
    expect_same_scene(a, whole(text, path));
  }
  EXPECT_GT(split_body_sections(many)->sections.size(), 2u);
}

TEST(BodySections, AMistakeInAnySectionIsNamedAtItsLineOfTheFile) {
  // The same message as the whole tree gives: the section's lines are counted from the file's start.
  const test::TempDir dir("body_sections_errors");
  const auto both = [&](const std::string& text) {
    const fs::path path = dir.write("s.toml", text);
    const std::string sections = outcome([&] { return load_scene(path); });
    EXPECT_EQ(sections, outcome([&] { return whole(text, path); }));
    return sections;
  };
  std::string text = kHead;
  for (int i = 0; i < 700; ++i) text += body(i);
  std::string bad = text;
  bad.replace(bad.find("density = 1000.0", bad.find("name = \"b600\"")), 16, "density = -1.0");
  EXPECT_NE(both(bad).find("body 'b600'"), std::string::npos);
  std::string unknown = text;
  unknown.replace(unknown.find("name = \"b555\""), 4, "nmae");
  const std::string u = both(unknown);
  EXPECT_NE(u.find("[[bodies]] #556: "), std::string::npos) << u;
  std::string duplicate = text;
  duplicate.replace(duplicate.find("name = \"b444\""), 13, "name = \"b4\"");
  const std::string d = both(duplicate);
  EXPECT_NE(d.find("duplicate name \"b4\" (first defined at line "), std::string::npos) << d;
  // A syntax error inside a section: toml++'s message, at the file's line.
  std::string syntax = text;
  syntax.replace(syntax.find("type = \"box\"", syntax.find("name = \"b333\"")), 12, "type = box\"");
  const std::string m = both(syntax);
  EXPECT_NE(m.find("TOML syntax error"), std::string::npos) << m;
  const size_t line =
      1 + static_cast<size_t>(std::count(
              syntax.begin(), syntax.begin() + static_cast<std::ptrdiff_t>(syntax.find("type = box")), '\n'));
  EXPECT_NE(m.find(fmt::format("s.toml:{}:", line)), std::string::npos) << m;
}

}  // namespace
}  // namespace tumble
