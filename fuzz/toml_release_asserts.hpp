// Forced include (-include) for toml++ in the fuzz build (cmake/Sanitizers.cmake): toml++'s own
// internal assertions behave as in the library that ships, Debian's libtomlplusplus.so, built by
// GCC with NDEBUG, where TOML_ASSERT and TOML_ASSERT_ASSUME expand to nothing.
//
// Why: the fuzz build compiles toml++ 3.3 from its headers without NDEBUG, and its parser asserts
// preconditions that it then handles itself; e.g. "[#a]" fails
// `TOML_ASSERT_ASSUME(is_bare_key_character
// (*cp) || …)` in parse_key() (parser.inl:3037), while the shipped library reports the syntax error
// "expected bare key starting character" (regression test:
// tests/common/test_config_fuzz_regressions .cpp). Under clang with NDEBUG that assertion would
// become __builtin_assume, i.e. undefined behaviour, so neither the debug nor the clang-release
// form is what mastrom runs.
#pragma once
#define TOML_ASSERT(expr) static_cast<void>(0)
