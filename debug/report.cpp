#include "debug/report.h"

#include <bit>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "scene/scene_file.h"

namespace rast {
namespace {

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string hexColor(Rgb c) {
  char buffer[8];
  std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", c.r, c.g, c.b);
  return buffer;
}

// Numbers right-aligned, as in the text table.
bool looksNumeric(const std::string& s) {
  return !s.empty() && s.find_first_not_of("0123456789.-+e") == std::string::npos;
}

std::string table(const TableData& t, const std::string& cssClass = "") {
  std::string h = "<table" + (cssClass.empty() ? "" : " class=\"" + cssClass + "\"") + ">\n<thead><tr>";
  for (const std::string& c : t.header) h += "<th>" + escape(c) + "</th>";
  h += "</tr></thead>\n<tbody>\n";
  for (const auto& row : t.rows) {
    h += "<tr>";
    for (const std::string& c : row) {
      if (c.size() == 7 && c[0] == '#')  // a colour: shown as a swatch with its code
        h += "<td><span class=\"swatch\" style=\"background:" + c + "\"></span>" + c + "</td>";
      else
        h += std::string(looksNumeric(c) ? "<td class=\"n\">" : "<td>") + escape(c) + "</td>";
    }
    h += "</tr>\n";
  }
  return h + "</tbody>\n</table>\n";
}

constexpr const char* kStyle = R"(body{font-family:system-ui,sans-serif;margin:2em;color:#222;max-width:1400px}
h1{font-size:1.5em}h2{font-size:1.2em;margin-top:2em;border-bottom:1px solid #ccc}
table{border-collapse:collapse;font-size:0.9em}th,td{border:1px solid #ccc;padding:2px 8px}
th{background:#f0f0f0}td.n{text-align:right;font-family:monospace}
.swatch{display:inline-block;width:1em;height:1em;margin-right:0.4em;vertical-align:middle}
figure{display:inline-block;margin:0 1.5em 1.5em 0;vertical-align:top;max-width:700px}
figure img{max-width:100%;image-rendering:pixelated;border:1px solid #888}
figcaption{font-size:0.85em;color:#444}code{background:#f4f4f4;padding:1px 4px}
)";

// Counts, after everything loaded, the images that decoded and the tables whose cells are all
// filled, into data attributes of <body> (and a line at the end of the page).
constexpr const char* kCheckScript = R"(<script>
window.addEventListener('load', function () {
  var images = Array.prototype.slice.call(document.images);
  var loaded = images.filter(function (i) { return i.complete && i.naturalWidth > 0; }).length;
  var tables = Array.prototype.slice.call(document.querySelectorAll('table'));
  var filled = tables.filter(function (t) {
    var cells = Array.prototype.slice.call(t.querySelectorAll('td'));
    return cells.length > 0 && cells.every(function (c) { return c.textContent.trim() !== ''; });
  }).length;
  document.body.setAttribute('data-images-loaded', loaded);
  document.body.setAttribute('data-tables-filled', filled);
  document.getElementById('check').textContent =
      loaded + ' of ' + images.length + ' images loaded, ' + filled + ' of ' + tables.length +
      ' tables filled';
});
</script>
)";

}  // namespace

Status htmlReport(const ReportInput& in, std::string& html) {
  const int tableCount = 5 + (in.precision ? 1 : 0);
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
                  escape(in.title) + "</title>\n<style>" + kStyle + "</style>\n</head>\n";
  h += "<body data-images-expected=\"" + std::to_string(in.images.size()) +
       "\" data-tables-expected=\"" + std::to_string(tableCount) + "\">\n";
  h += "<h1>" + escape(in.title) + "</h1>\n";
  if (!in.commandLine.empty()) h += "<p><code>" + escape(in.commandLine) + "</code></p>\n";
  h += "<h2>Scene</h2>\n" + table(in.scene);
  h += "<h2>Pipeline state per draw</h2>\n" + table(in.drawStates);
  h += "<h2>Statistics</h2>\n<p>Counters per draw and for the frame (rows zero everywhere left "
       "out). Derived: vertex.cache_hits = indices - shader invocations; raster.samples_tested = "
       "64 per partial tile; early or late depth as the draw's state places the test.</p>\n" +
       table(in.statistics);
  h += "<h2>Time per stage</h2>\n<p>Wall time in milliseconds; unlike the counters it varies from "
       "run to run. A draw of at least two chunks of 4096 triangles per thread bins each chunk in "
       "the task that set it up: its clip_setup includes binning, and bin is the sort.</p>\n" +
       table(in.timings);
  h += "<h2>Images</h2>\n";
  for (const ReportImage& image : in.images) {
    std::vector<unsigned char> png;
    if (Status s = encodePng(image.image, png); !s) return s;
    h += "<figure><img alt=\"" + escape(image.title) + "\" src=\"" + pngDataUri(png) + "\">" +
         "<figcaption><b>" + escape(image.title) + ".</b> " + escape(image.caption) +
         "</figcaption></figure>\n";
  }
  h += "<h2>Triangles in the zoomed tile</h2>\n" + table(in.tileTriangles);
  h += "<h2>Precision laboratory</h2>\n";
  if (in.precision)
    h += "<p>From <code>" + escape(in.precisionSource) + "</code>.</p>\n" + table(*in.precision);
  else
    h += "<p>No table given (<code>--precision-table file.csv</code>).</p>\n";
  h += "<p id=\"check\"></p>\n";
  h += kCheckScript;
  h += "</body>\n</html>\n";
  html = std::move(h);
  return Status::ok();
}

Status parseCsvTable(const std::string& text, const std::string& name, TableData& out) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false, fieldStarted = false;
  size_t line = 1, rowLine = 1;
  auto endRow = [&]() -> Status {
    if (!fieldStarted && row.empty() && field.empty()) return Status::ok();  // blank line
    row.push_back(field);
    field.clear();
    fieldStarted = false;
    if (!rows.empty() && row.size() != rows.front().size())
      return Status::error(name + ":" + std::to_string(rowLine) + ": expected " +
                           std::to_string(rows.front().size()) + " fields, found " +
                           std::to_string(row.size()));
    rows.push_back(std::move(row));
    row.clear();
    return Status::ok();
  };
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        if (c == '\n') ++line;
        field += c;
      }
    } else if (c == '"' && field.empty()) {
      quoted = fieldStarted = true;
    } else if (c == ',') {
      row.push_back(field);
      field.clear();
      fieldStarted = true;
    } else if (c == '\n') {
      if (Status s = endRow(); !s) return s;
      rowLine = ++line;
    } else if (c != '\r') {
      field += c;
      fieldStarted = true;
    }
  }
  if (quoted) return Status::error(name + ":" + std::to_string(rowLine) + ": unterminated quoted field");
  if (Status s = endRow(); !s) return s;
  if (rows.size() < 2) return Status::error(name + ": expected a header row and at least one row");
  out.header = rows.front();
  out.rows.assign(rows.begin() + 1, rows.end());
  return Status::ok();
}

Status readCsvTable(const std::string& path, TableData& out) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return Status::error(path + ": cannot open file");
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  return parseCsvTable(text, path, out);
}

TableData tileTriangleTable(const DebugData& d) {
  TableData t;
  t.header = {"draw", "triangle id", "colour", "covered samples"};
  for (size_t i = 0; i < d.zoomTriangles.size(); ++i) {
    const ZoomTriangle& z = d.zoomTriangles[i];
    t.rows.push_back({z.label, std::to_string(z.triangleId), hexColor(zoomColor(i)),
                      std::to_string(std::popcount(z.mask))});
  }
  if (t.rows.empty()) t.rows.push_back({"(none)", "-", "-", "0"});
  return t;
}

TableData drawStateTable(const FramePlan& plan) {
  TableData t;
  t.header = {"draw", "triangles", "shader", "cull", "front face", "depth compare", "depth write",
              "early depth", "colour write", "precision"};
  for (const FrameDraw& d : plan.draws) {
    const PipelineState& s = d.state;
    t.rows.push_back({d.label, std::to_string(d.triangleCount), d.shader, cullModeName(s.cullMode),
                      frontFaceName(s.frontFace), compareOpName(s.depth.compare),
                      s.depth.write ? "yes" : "no", s.depth.early ? "yes" : "no",
                      s.colorWrite ? "yes" : "no", s.format.name()});
  }
  return t;
}

}  // namespace rast
