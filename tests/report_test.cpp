// The HTML report, opened in headless Chromium: every image decodes and every table is filled
// (the report's own script counts them after loading). Chromium is a test dependency installed by
// scripts/install-deps.sh; without it these tests fail, they do not skip.
#include <gtest/gtest.h>

#include <cstdlib>

#include "debug/report.h"
#include "tool_process.h"

namespace rast {
namespace {

using testing_tools::readWholeFile;
using testing_tools::runProcess;
using testing_tools::runTool;
using testing_tools::TempFolder;

bool onPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::string dirs = path;
  size_t start = 0;
  while (start <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    if (access((dirs.substr(start, end - start) + "/" + program).c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

struct PageCounts {
  int imagesLoaded = -1, tablesFilled = -1, imagesExpected = -1, tablesExpected = -1;
};

// Loads the page in headless Chromium and reads back what its script recorded on <body>.
PageCounts openInBrowser(const std::filesystem::path& html, const TempFolder& dir) {
  PageCounts c;
  if (!onPath("chromium")) {
    ADD_FAILURE() << "chromium is not installed: the report test needs it (scripts/install-deps.sh "
                     "installs Debian's chromium package)";
    return c;
  }
  const testing_tools::ProcessResult r = runProcess(
      "chromium", {"--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
                   "--user-data-dir=" + (dir / "chromium-profile").string(),
                   "--virtual-time-budget=5000", "--dump-dom", "file://" + html.string()},
      dir);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  const size_t body = r.out.find("<body ");
  if (body == std::string::npos) {
    ADD_FAILURE() << "no <body> in chromium's output: " << r.out.substr(0, 500) << r.err.substr(0, 500);
    return c;
  }
  const std::string attributes = r.out.substr(body, r.out.find('>', body) - body);
  auto read = [&](const std::string& name) {
    const size_t at = attributes.find(name + "=\"");
    return at == std::string::npos ? -1 : std::atoi(attributes.c_str() + at + name.size() + 2);
  };
  c.imagesLoaded = read("data-images-loaded");
  c.tablesFilled = read("data-tables-filled");
  c.imagesExpected = read("data-images-expected");
  c.tablesExpected = read("data-tables-expected");
  return c;
}

int occurrences(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

TEST(Report, EveryImageLoadsAndEveryTableIsFilledInTheBrowser) {
  TempFolder dir;
  dir.write("precision.csv", "format,max error (px),\"note, quoted\"\n24.4,0.03125,ok\n16.8,0.001953125,\"a \"\"b\"\"\"\n");
  const auto html = dir / "report.html";
  const testing_tools::ProcessResult r =
      runTool({"--width", "64", "--height", "40", "--cull", "back", "--report", html.string(),
               "--precision-table", (dir / "precision.csv").string(), "--tile", "3,2"},
              dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string text = readWholeFile(html);
  // The render and six debugging images, all embedded; scene, state, statistics, timings, tile
  // triangles and precision tables. Nothing is fetched from anywhere.
  EXPECT_EQ(occurrences(text, "<img "), 7);
  EXPECT_EQ(occurrences(text, "src=\"data:image/png;base64,"), 7);
  EXPECT_EQ(occurrences(text, "<table"), 6);
  EXPECT_EQ(occurrences(text, "http://") + occurrences(text, "https://"), 0);
  EXPECT_NE(text.find("<td>a &quot;b&quot;</td>"), std::string::npos);
  EXPECT_NE(text.find("Coverage of tile 3,2"), std::string::npos);

  const PageCounts page = openInBrowser(html, dir);
  EXPECT_EQ(page.imagesExpected, 7);
  EXPECT_EQ(page.tablesExpected, 6);
  EXPECT_EQ(page.imagesLoaded, 7);
  EXPECT_EQ(page.tablesFilled, 6);

  // The check itself can fail: a corrupt image and an empty cell are both noticed.
  std::string broken = text;
  const size_t image = broken.find("base64,") + 7;
  broken.replace(image, 16, "AAAAAAAAAAAAAAAA");
  const std::string filledCell = "<td class=\"n\">24.4</td>";
  const size_t cell = broken.find(filledCell);
  ASSERT_NE(cell, std::string::npos);
  broken.replace(cell, filledCell.size(), "<td> </td>");
  const auto brokenHtml = dir.write("broken.html", broken);
  const PageCounts bad = openInBrowser(brokenHtml, dir);
  EXPECT_EQ(bad.imagesLoaded, 6);
  EXPECT_EQ(bad.tablesFilled, 5);
}

TEST(Report, WithoutAPrecisionTableItSaysSo) {
  TempFolder dir;
  const auto html = dir / "report.html";
  ASSERT_EQ(runTool({"--width", "32", "--height", "32", "--report", html.string()}, dir).exitCode, 0);
  const std::string text = readWholeFile(html);
  EXPECT_EQ(occurrences(text, "<table"), 5);
  EXPECT_NE(text.find("No table given (<code>--precision-table file.csv</code>)"), std::string::npos);
  EXPECT_NE(text.find("data-tables-expected=\"5\""), std::string::npos);
}

TEST(CsvTable, QuotedFieldsAndErrors) {
  TableData t;
  ASSERT_TRUE(parseCsvTable("a,b\n\"1,5\",\"say \"\"hi\"\"\"\r\n\n3,4\n", "t.csv", t).isOk());
  EXPECT_EQ(t.header, (std::vector<std::string>{"a", "b"}));
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.rows[0], (std::vector<std::string>{"1,5", "say \"hi\""}));
  EXPECT_EQ(t.rows[1], (std::vector<std::string>{"3", "4"}));
  EXPECT_EQ(parseCsvTable("a,b\n1,2\n3\n", "t.csv", t).message(), "t.csv:3: expected 2 fields, found 1");
  EXPECT_EQ(parseCsvTable("a,b\n", "t.csv", t).message(), "t.csv: expected a header row and at least one row");
  EXPECT_EQ(parseCsvTable("a,b\n\"1,2\n", "t.csv", t).message(), "t.csv:2: unterminated quoted field");
  EXPECT_EQ(readCsvTable("/no/such/file.csv", t).message(), "/no/such/file.csv: cannot open file");
}

}  // namespace
}  // namespace rast
