#pragma once
// A scene's [[bodies]] tables taken out of its text, to be parsed a section at a time.
//
// toml++ builds a tree of the whole document: a node per value, 3 KB and 42 allocations per [[bodies]]
// table. For a scene of 10⁵ bodies that tree is 400 MB, and building and freeing it cost more than
// everything else the scene's set-up does (bench/scene_setup). No TOML reader Debian packages parses a
// document a part at a time (bench/toml_readers.sh), so tumble cuts the text into the [[bodies]]
// sections and the rest, and lets toml++ parse each: the rest as one document, every section (a few
// dozen bodies) as its own, its tree freed before the next is parsed. Each section starts at a line
// of the file, so a message about it adds the line the section starts at (TomlFile::first_line).
//
// This is a lexer, not a parser: it only follows strings, comments and brackets far enough to find the
// lines that are table headers, and leaves every judgement about the TOML to toml++. Where the text is
// anything but plain — a multi-line string, a header with quoted or dotted-and-spaced keys, a
// [bodies.x] table outside a [[bodies]] section, brackets that do not balance — it declines, and the
// scene is parsed whole, as it always was; so is a scene whose rest still defines `bodies`. Both ways
// give the same Scene or the same message (tests/io/body_sections_test.cpp; the scene fuzzer compares
// the two on every input).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tumble::scene {

struct BodySections {
  /// The text without the sections: every line of theirs left empty, so that lines keep their numbers.
  std::string rest;
  /// A run of consecutive [[bodies]] tables with their sub-tables ([bodies.shape], [[bodies.parts]]),
  /// in file order, and the line of the file it starts at.
  struct Section {
    std::string_view text;
    std::uint32_t first_line;
  };
  std::vector<Section> sections;
  size_t bodies = 0;  ///< the [[bodies]] headers in all of them
};

/// A section holds consecutive bodies up to about this many bytes: small enough that its tree stays in
/// cache, large enough that a parse's fixed cost does not count.
inline constexpr size_t kBodySectionBytes = 64 * 1024;

/// The [[bodies]] sections of `text` (a view into it) and the rest; nullopt when the text has no
/// [[bodies]] table or is not plain enough to split (above): parse it whole.
std::optional<BodySections> split_body_sections(std::string_view text);

}  // namespace tumble::scene
