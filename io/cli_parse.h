#pragma once
// Command-line parsing shared by mfp's programs: `--help` exits 0; a bad flag, a value out
// of range or a missing file exits 2, DESIGN.md's bad-input code, with CLI11's message
// naming the flag (CLI11's own codes, e.g. 105 for a failed check, are not ours).
#include <CLI/CLI.hpp>

#define MFP_CLI_PARSE(app, argc, argv)                \
  do {                                                \
    try {                                             \
      (app).parse((argc), (argv));                    \
    } catch (const CLI::ParseError& parse_error) {    \
      return (app).exit(parse_error) == 0 ? 0 : 2;    \
    }                                                 \
  } while (false)
