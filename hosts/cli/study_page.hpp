#pragma once
// The page of an uncertainty study (`mechgraph study --out DIR` writes DIR/report.html): the
// parameters, per output its summary and histogram against its spec limits, a chart of its Sobol'
// indices with their intervals, and the events. Self-contained HTML with inline SVG drawn here
// (bars and lines, no plotting program); every text from the scene goes through html_text.
#include <mechgraph/uncertainty/study_answers.hpp>

#include <string>

namespace mechgraph::cli {

std::string study_page(const std::string& title, const StudySpec& spec, const StudyAnswers& answers);

}  // namespace mechgraph::cli
