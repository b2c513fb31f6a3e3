// Running the report program (cli/cmd_report.cpp) from other commands: `mastrom study` writes a
// report of each study it ran.
#pragma once

#include <string>
#include <vector>

namespace mastrom::cli {

struct ReportRequest {
  std::vector<std::string> files;
  std::string out_dir;        ///< "" = report/ next to the first file
  std::string screen_metric;  ///< "" = every metric
  std::string study;          ///< "" = every study of a study.h5 among the files
};

/// Write the report of `request` (figures + index.html) and print "wrote DIR/index.html". Throws
/// IoError (bad input or file) or Error (anything else) with a one-line message.
void writeReport(const ReportRequest& request);

}  // namespace mastrom::cli
