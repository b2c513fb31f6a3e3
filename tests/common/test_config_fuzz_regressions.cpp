// Regression tests for the inputs fuzz/fuzz_config.cpp found (issue #7). Each test holds the
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

}  // namespace
}  // namespace mastrom
