// Regression tests for the inputs fuzz/fuzz_config.cpp found. Each test holds the
// crashing input inline and checks the behaviour the fuzzer demands: a one-line InputError naming
// the key, or an accepted configuration that reads back to itself through toToml().
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "common/config.hpp"
#include "common/error.hpp"

namespace mastrom {
namespace {

/// The InputError message of applyConfigOverrides(Config{}, overrides), or "" when accepted.
std::string overrideRefusal(const std::vector<std::string>& overrides) {
  try {
    applyConfigOverrides(Config{}, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Found: `--set output.file="run 1.h5<0xff>` (an unterminated TOML string, hence taken as a bare
// string) was accepted, and the resolved config, written by toToml(), then failed to parse: TOML
// text must be UTF-8. The override is now refused with the key and the offending byte.
TEST(ConfigFuzzRegression, BareOverrideThatIsNotUtf8IsRefused) {
  const std::string message = overrideRefusal({"output.file=\"run 1.h5\xff"});
  EXPECT_NE(message.find("output.file"), std::string::npos) << message;
  EXPECT_NE(message.find("not valid UTF-8 (byte 0xff at offset 9)"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  // The other malformed UTF-8 forms (RFC 3629 §4): overlong, surrogate, above U+10FFFF, truncated.
  for (const char* bad :
       {"\xc0\xaf", "\xe0\x80\xaf", "\xed\xa0\x80", "\xf4\x90\x80\x80", "a\xe2\x82"}) {
    EXPECT_NE(overrideRefusal({std::string("output.file=") + bad}).find("not valid UTF-8"),
              std::string::npos)
        << bad;
  }
}

TEST(ConfigFuzzRegression, BareUtf8OverrideRoundTrips) {
  // 2-, 3- and 4-byte sequences at the edges of the valid ranges.
  const std::string file = "run \xc3\xa9 \xe2\x82\xac \xed\x9f\xbf \xf4\x8f\xbf\xbf.h5";
  const Config c = applyConfigOverrides(Config{}, {"output.file=" + file});
  EXPECT_EQ(c.output.file, file);
  EXPECT_EQ(parseConfigText(toToml(c), "round trip"), c);
}

// Found: "[#simulation]" trips an internal assertion of toml++ 3.3 (parser.inl, parse_key) when
// toml++ is compiled from its headers without NDEBUG (the fuzz build); the shipped library reports
// a syntax error, which is what mastrom must print.
TEST(ConfigFuzzRegression, CommentSignInTableHeaderIsASyntaxError) {
  try {
    parseConfigText("[#simulation]\nend_time = 0.3\n", "hash.toml");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("hash.toml:1:"), std::string::npos) << message;
    EXPECT_NE(message.find("TOML syntax error"), std::string::npos) << message;
  }
}

// Found: "a = 1 §" — any of many non-ASCII characters (U+00A1…U+0499 among them) where toml++
// 3.3.0 skips whitespace reaches __builtin_unreachable() in is_non_ascii_horizontal_whitespace
// (UBSan; upstream marzer/tomlplusplus#190). TOML allows non-ASCII only in strings and comments,
// so mastrom refuses it elsewhere before toml++ sees it, naming line and column.
TEST(ConfigFuzzRegression, NonAsciiOutsideStringsIsASyntaxErrorNotUndefinedBehaviour) {
  for (const char* text : {"[mast]\nmodules = 4 \xc2\xa7\n", "[mast]\nmodules = 4\xc3\xa9\n",
                           "[mast]\nmodules\xd0\x96 = 4\n"}) {
    try {
      parseConfigText(text, "u.toml");
      FAIL() << "accepted: " << text;
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("u.toml:2:"), std::string::npos) << message;
      EXPECT_NE(message.find("non-ASCII character outside a string or comment"),
                std::string::npos)
          << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }
  // Column of the offending byte: "modules = 4 §" has it at column 13.
  try {
    parseConfigText("[mast]\nmodules = 4 \xc2\xa7\n", "u.toml");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("u.toml:2:13:"), std::string::npos) << e.what();
  }
  // Inside strings (all four kinds) and comments non-ASCII is fine.
  const Config c = parseConfigText(
      "# \xc3\xbc\xc2\xa7 comment\n[output]\nfile = \"r\xc3\xa9sum\xc3\xa9 \\\" \xc2\xa7.h5\" # \xc2\xa7\n"
      "[drive]\nlaw = '''cubic''' # \xc3\xa9 'x'\n",
      "ok.toml");
  EXPECT_EQ(c.output.file, "r\xc3\xa9sum\xc3\xa9 \" \xc2\xa7.h5");
  EXPECT_NO_THROW(parseConfigText("[output]\nfile = '\xc2\xa7'\n", "lit.toml"));
  EXPECT_NO_THROW(parseConfigText("[output]\nfile = \"\"\"\xc2\xa7\n\xc2\xa7\"\"\"\n", "ml.toml"));
  // An override with non-ASCII outside quotes is a bare string (never parsed as TOML): a file
  // name is accepted, a number is a clean type error naming the key.
  EXPECT_EQ(applyConfigOverrides(Config{}, {"output.file=r\xc3\xa9sum\xc3\xa9.h5"}).output.file,
            "r\xc3\xa9sum\xc3\xa9.h5");
  const std::string message = overrideRefusal({"mast.modules=4\xc2\xa7"});
  EXPECT_NE(message.find("mast.modules"), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

}  // namespace
}  // namespace mastrom
