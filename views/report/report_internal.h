// The report writer's parts that live in their own files (report.h is the interface).
#pragma once
#include <string>

#include "views/analysis/compare.h"
#include "views/capture/capture.h"

namespace gb {

// The page's text, carried inside the binary (views/report/page.html, page.js, texels.js and index.js,
// cmake/EmbedText.cmake).
const char* reportPageHtml();
const char* reportPageJs();
const char* reportTexelsJs();
const char* reportIndexJs();

// One group's chunk files STEM.<chunk>.js and, in `meta`, what report.js says of it (report_data.cpp).
bool writeGroupData(const Capture& a, const Capture& b, const GroupResult& g, const std::string& stem,
                    nlohmann::json& meta, std::string& error);
// Everything of one pair's report into the existing folder `dir` (report_page.cpp).
bool writeReportContents(const Capture& a, const Capture& b, const CompareReport& report, const std::string& dir,
                         std::string& error);
// The pairs index page's thumbnails of one pair into `dir` (thumbnail.cpp): thumb_a.png (A's `final`
// or first colour view) and thumb_diff.png (the worst group's heat map), at most 160 pixels wide.
// `out` gets {"a": prefix + file, "diff": ...}, null for a picture the pair has none of.
bool writeThumbnails(const Capture& a, const CompareReport& report, const std::string& dir, const std::string& prefix,
                     nlohmann::json& out, std::string& error);
// index.html (the page, which reads report.js) and report.js calling gblensReport(`data`).
bool writePage(const std::string& dir, const nlohmann::json& data, std::string& error);

}  // namespace gb
