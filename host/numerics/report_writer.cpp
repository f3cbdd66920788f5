#include "numerics/report_writer.h"

#include "image/image_io.h"
#include "util/error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <numeric>
#include <ostream>
#include <sstream>

namespace vkray::numerics {

namespace {

std::string printed(const char* format, double v) {
    char text[64];
    std::snprintf(text, sizeof text, format, v);
    return text;
}

// Short form for the text table and plot labels; full form for files.
std::string shortText(const ReportValue& v) {
    switch (v.kind) {
    case ReportValue::Empty: return "-";
    case ReportValue::Integer: return std::to_string(v.integer);
    case ReportValue::Text: return v.text;
    case ReportValue::Number:
        if (v.number == 0) return "0";
        return printed(std::abs(v.number) >= 1e-3 && std::abs(v.number) < 1e5 ? "%.4g" : "%.2e",
                       v.number);
    }
    return "";
}

std::string fullNumber(double v) {
    return std::isfinite(v) ? printed("%.9g", v) : "";
}

std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string out = "\"";
    for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

// A cell in JSON: numbers as CSV prints them (9 significant digits), so that
// both files hold the same values; a non-finite number is null.
nlohmann::ordered_json jsonValue(const ReportValue& v) {
    switch (v.kind) {
    case ReportValue::Empty: return nullptr;
    case ReportValue::Integer: return v.integer;
    case ReportValue::Text: return v.text;
    case ReportValue::Number:
        if (!std::isfinite(v.number)) return nullptr;
        return std::stod(fullNumber(v.number));
    }
    return nullptr;
}

std::string xml(const std::string& s) {
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

// A log10 axis over the positive values, whole decades; values <= 0 sit on
// an extra line one decade below, labelled 0.
struct LogAxis {
    int lo = 0, hi = 1;  // decades
    bool zeroLine = false;

    explicit LogAxis(const std::vector<double>& values) {
        double mn = std::numeric_limits<double>::infinity(), mx = 0;
        for (double v : values) {
            if (!(v > 0) || !std::isfinite(v)) {
                zeroLine = zeroLine || v <= 0;
                continue;
            }
            mn = std::min(mn, v);
            mx = std::max(mx, v);
        }
        if (mx > 0) {
            lo = int(std::floor(std::log10(mn)));
            hi = std::max(lo + 1, int(std::ceil(std::log10(mx))));
        }
    }
    int first() const { return zeroLine ? lo - 1 : lo; }
    // Position in [0, 1] along the axis.
    double at(double v) const {
        const double decade = v > 0 && std::isfinite(v) ? std::log10(v) : double(first());
        return (std::clamp(decade, double(first()), double(hi)) - first()) / double(hi - first());
    }
};

std::string decadeLabel(int decade) {
    if (decade == 0) return "1";
    if (decade == 1) return "10";
    return "1e" + std::to_string(decade);
}

const char* kPalette[] = {"#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e",
                          "#8c564b", "#17becf", "#e377c2"};

// Words broken into lines of at most `width` characters (a longer word keeps its own line).
std::vector<std::string> wrapped(const std::string& text, size_t width) {
    std::vector<std::string> lines;
    std::istringstream words(text);
    for (std::string word; words >> word;) {
        if (!lines.empty() && lines.back().size() + 1 + word.size() <= width)
            lines.back() += " " + word;
        else
            lines.push_back(word);
    }
    return lines;
}

// A PNG's size from its IHDR chunk (bytes 16..23); 0 x 0 when it has none.
std::pair<int, int> pngSize(const std::string& png) {
    if (png.size() < 24 || png.compare(12, 4, "IHDR") != 0) return {0, 0};
    const auto at = [&](size_t i) {
        return int(std::uint8_t(png[i])) << 24 | int(std::uint8_t(png[i + 1])) << 16 |
               int(std::uint8_t(png[i + 2])) << 8 | int(std::uint8_t(png[i + 3]));
    };
    return {at(16), at(20)};
}

// Pictures smaller than this are shown enlarged by a whole factor (pixels stay square).
constexpr int kLeastShownWidth = 160;
constexpr double kColourScaleWidth = 180;  // colourScaleSvg's

std::string figureHtml(const Figure& figure) {
    const auto [width, height] = pngSize(figure.png);
    const int zoom =
        width > 0 && width < kLeastShownWidth ? (kLeastShownWidth + width - 1) / width : 1;
    // The figure as wide as its picture (or its colour scale), so that a long
    // caption wraps under the picture instead of widening it.
    const int shown = std::max(width * zoom, figure.scale ? int(kColourScaleWidth) : 0);
    std::ostringstream h;
    h << "<figure style=\"width: " << shown << "px\"><img src=\"data:image/png;base64,"
      << base64(figure.png) << "\" width=\"" << width * zoom << "\" height=\"" << height * zoom
      << "\" alt=\"" << xml(figure.caption) << "\"/><figcaption>" << xml(figure.caption)
      << "</figcaption>";
    if (figure.scale) h << colourScaleSvg(*figure.scale, figure.scaleLabel);
    h << "</figure>";
    return h.str();
}

std::string galleryHtml(const Gallery& gallery) {
    std::ostringstream h;
    h << "<section class=\"gallery\">\n<h2>" << xml(gallery.title) << "</h2>\n";
    for (const std::string& p : gallery.paragraphs) h << "<p>" << xml(p) << "</p>\n";
    if (!gallery.legend.empty()) {
        h << "<div class=\"legend\">";
        for (const LegendEntry& entry : gallery.legend)
            h << "<span class=\"entry\"><span class=\"swatch\" style=\"background: "
              << xml(entry.colour) << "\"></span>" << xml(entry.text) << "</span>";
        h << "</div>\n";
    }
    h << "<div class=\"groups\">\n";
    for (const FigureGroup& group : gallery.groups) {
        h << "<div class=\"group\">\n<h3>" << xml(group.title) << "</h3>\n";
        if (!group.note.empty()) h << "<p class=\"note\">" << xml(group.note) << "</p>\n";
        h << "<div class=\"figures\">";
        for (const Figure& figure : group.figures) h << figureHtml(figure);
        h << "</div>\n</div>\n";
    }
    h << "</div>\n</section>\n";
    return h.str();
}

}  // namespace

std::string formatTable(const ReportTable& table) {
    std::vector<size_t> widths;
    for (const std::string& c : table.columns) widths.push_back(c.size());
    for (const auto& row : table.rows)
        for (size_t i = 0; i < row.size() && i < widths.size(); ++i)
            widths[i] = std::max(widths[i], shortText(row[i]).size());
    std::ostringstream out;
    const auto line = [&](const std::vector<std::string>& cells) {
        for (size_t i = 0; i < cells.size(); ++i) {
            const bool left = i == 0 || i == 1;
            const std::string pad(widths[i] - cells[i].size(), ' ');
            out << (i ? "  " : "") << (left ? cells[i] + pad : pad + cells[i]);
        }
        out << "\n";
    };
    line(table.columns);
    for (const auto& row : table.rows) {
        std::vector<std::string> cells;
        for (const ReportValue& v : row) cells.push_back(shortText(v));
        line(cells);
    }
    return out.str();
}

std::string toCsv(const ReportTable& table) {
    std::ostringstream out;
    for (size_t i = 0; i < table.columns.size(); ++i)
        out << (i ? "," : "") << csvField(table.columns[i]);
    out << "\n";
    for (const auto& row : table.rows) {
        for (size_t i = 0; i < row.size(); ++i) {
            const ReportValue& v = row[i];
            out << (i ? "," : "");
            if (v.kind == ReportValue::Number)
                out << fullNumber(v.number);
            else if (v.kind == ReportValue::Integer)
                out << v.integer;
            else if (v.kind == ReportValue::Text)
                out << csvField(v.text);
        }
        out << "\n";
    }
    return out.str();
}

std::string toJson(const Report& report) {
    // ordered_json: the members stay in the order written, the rows' in the
    // table's column order.
    nlohmann::ordered_json json;
    json["title"] = report.title;
    json["notes"] = report.paragraphs;
    json["columns"] = report.table.columns;
    json["rows"] = nlohmann::ordered_json::array();
    for (const std::vector<ReportValue>& row : report.table.rows) {
        nlohmann::ordered_json& object =
            json["rows"].emplace_back(nlohmann::ordered_json::object());
        for (size_t i = 0; i < row.size(); ++i) object[report.table.columns[i]] = jsonValue(row[i]);
    }
    // Text that is not UTF-8 (a Latin-1 name from a scene file) is written
    // with U+FFFD in its place rather than failing the report.
    return json.dump(2, ' ', false, nlohmann::ordered_json::error_handler_t::replace) + "\n";
}

std::string toSvg(const Plot& plot) {
    // The plot area, then the legend's column on the right.
    constexpr double legendWidth = 160, W = 420 + legendWidth, H = 300, left = 64,
                     right = 16 + legendWidth, top = 28, bottom = 44;
    std::vector<double> xs, ys;
    for (const PlotPoint& p : plot.points) {
        xs.push_back(p.x);
        ys.push_back(p.y);
    }
    const LogAxis ax(xs), ay(ys);
    const auto px = [&](double x) { return left + ax.at(x) * (W - left - right); };
    const auto py = [&](double y) { return H - bottom - ay.at(y) * (H - top - bottom); };
    std::ostringstream s;
    s << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H
      << "\" viewBox=\"0 0 " << W << " " << H
      << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    s << "<title>" << xml(plot.title) << "</title>\n";
    s << "<rect x=\"0\" y=\"0\" width=\"" << W << "\" height=\"" << H << "\" fill=\"white\"/>\n";
    s << "<text x=\"" << (left + W - right) / 2
      << "\" y=\"16\" text-anchor=\"middle\" font-weight=\"bold\">" << xml(plot.title)
      << "</text>\n";
    for (int d = ax.first(); d <= ax.hi; ++d) {
        const double x = px(d < ax.lo ? 0.0 : std::pow(10.0, d));
        s << "<line x1=\"" << x << "\" y1=\"" << top << "\" x2=\"" << x << "\" y2=\"" << H - bottom
          << "\" stroke=\"#ddd\"/>\n<text x=\"" << x << "\" y=\"" << H - bottom + 14
          << "\" text-anchor=\"middle\">" << (d < ax.lo ? "0" : decadeLabel(d)) << "</text>\n";
    }
    for (int d = ay.first(); d <= ay.hi; ++d) {
        const double y = py(d < ay.lo ? 0.0 : std::pow(10.0, d));
        s << "<line x1=\"" << left << "\" y1=\"" << y << "\" x2=\"" << W - right << "\" y2=\"" << y
          << "\" stroke=\"#ddd\"/>\n<text x=\"" << left - 4 << "\" y=\"" << y + 4
          << "\" text-anchor=\"end\">" << (d < ay.lo ? "0" : decadeLabel(d)) << "</text>\n";
    }
    s << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << W - left - right
      << "\" height=\"" << H - top - bottom << "\" fill=\"none\" stroke=\"#444\"/>\n";
    s << "<text x=\"" << (left + W - right) / 2 << "\" y=\"" << H - 8
      << "\" text-anchor=\"middle\">" << xml(plot.xLabel) << "</text>\n";
    s << "<text transform=\"translate(14 " << (top + H - bottom) / 2
      << ") rotate(-90)\" text-anchor=\"middle\">" << xml(plot.yLabel) << "</text>\n";
    // The Pareto front: by time, each point faster than all with less error.
    std::vector<PlotPoint> sorted = plot.points;
    std::sort(sorted.begin(), sorted.end(), [](const PlotPoint& a, const PlotPoint& b) {
        return a.x < b.x || (a.x == b.x && a.y < b.y);
    });
    std::string front;
    double bestY = std::numeric_limits<double>::infinity();
    for (const PlotPoint& p : sorted) {
        if (!(p.y < bestY)) continue;
        bestY = p.y;
        front += printed("%.1f", px(p.x)) + "," + printed("%.1f", py(p.y)) + " ";
    }
    if (!front.empty())
        s << "<polyline points=\"" << front
          << "\" fill=\"none\" stroke=\"#999\" stroke-dasharray=\"4 3\"/>\n";
    // Labels: the front's points first, then the others, each only where it
    // overlaps no label already placed (a crowded plot would otherwise be a
    // blot); every point keeps its label as a tooltip.
    struct Box {
        double x0, y0, x1, y1;
    };
    std::vector<Box> placed;
    std::vector<size_t> order(plot.points.size());
    std::iota(order.begin(), order.end(), size_t(0));
    const auto onFront = [&](const PlotPoint& p) {
        return std::none_of(plot.points.begin(), plot.points.end(), [&](const PlotPoint& q) {
            return (q.x < p.x && q.y <= p.y) || (q.x <= p.x && q.y < p.y);
        });
    };
    std::stable_partition(order.begin(), order.end(),
                          [&](size_t i) { return onFront(plot.points[i]); });
    std::string labels;
    for (const size_t i : order) {
        const PlotPoint& p = plot.points[i];
        const double x = px(p.x), y = py(p.y);
        const bool leftSide = x > W - right - 90;
        const double width = 6.2 * double(p.label.size());
        const Box box{leftSide ? x - 8 - width : x + 8, y - 17, leftSide ? x - 8 : x + 8 + width,
                      y - 4};
        if (std::any_of(placed.begin(), placed.end(), [&](const Box& b) {
                return box.x0 < b.x1 && b.x0 < box.x1 && box.y0 < b.y1 && b.y0 < box.y1;
            }))
            continue;
        placed.push_back(box);
        labels += "<text x=\"" + printed("%.1f", leftSide ? x - 8 : x + 8) + "\" y=\"" +
                  printed("%.1f", y - 6) + "\"" + (leftSide ? " text-anchor=\"end\"" : "") + ">" +
                  xml(p.label) + "</text>\n";
    }
    // A colour per series, in the order the series first appear.
    std::vector<std::string> series;
    const auto seriesOf = [](const PlotPoint& p) { return p.series.empty() ? p.label : p.series; };
    const auto colourOf = [&](const std::string& name) {
        const size_t k = size_t(std::find(series.begin(), series.end(), name) - series.begin());
        return kPalette[k % (sizeof kPalette / sizeof *kPalette)];
    };
    for (const PlotPoint& p : plot.points)
        if (std::find(series.begin(), series.end(), seriesOf(p)) == series.end())
            series.push_back(seriesOf(p));
    for (size_t i = 0; i < plot.points.size(); ++i) {
        const PlotPoint& p = plot.points[i];
        const char* color = colourOf(seriesOf(p));
        const double x = px(p.x), y = py(p.y);
        s << "<circle class=\"point\" cx=\"" << x << "\" cy=\"" << y << "\" r=\"5\" "
          << (p.flagged ? std::string("fill=\"white\" stroke=\"#d62728\" stroke-width=\"2\"")
                        : "fill=\"" + std::string(color) + "\"")
          << "><title>" << xml(p.label) << ": time " << shortText(ReportValue::num(p.x))
          << ", error " << shortText(ReportValue::num(p.y)) << "</title></circle>\n";
    }
    s << labels;
    // The legend: a line per series, then the hollow red points' meaning and
    // the front, as far as they are on the plot.
    constexpr size_t kLegendLine = 20;  // characters: 134 pixels at 11 px sans-serif
    const double legendX = W - legendWidth + 8, lineHeight = 15, lastLine = H - bottom;
    double y = top + 10;
    s << "<g class=\"legend\">\n<text x=\"" << legendX << "\" y=\"" << y
      << "\" font-weight=\"bold\">legend</text>\n";
    y += lineHeight;
    const auto entry = [&](const std::string& mark, const std::string& text) {
        const std::vector<std::string> lines = wrapped(text, kLegendLine);
        s << mark;
        for (size_t k = 0; k < lines.size(); ++k)
            s << "<text x=\"" << legendX + 18 << "\" y=\"" << y + 4 + lineHeight * double(k)
              << "\">" << xml(lines[k]) << "</text>\n";
        y += lineHeight * double(lines.size());
    };
    const bool anyFlagged = std::any_of(plot.points.begin(), plot.points.end(),
                                        [](const PlotPoint& p) { return p.flagged; });
    // Lines left for the series once the other entries have theirs.
    const long room = long((lastLine - y) / lineHeight) - (front.empty() ? 0 : 1) -
                      (anyFlagged ? long(wrapped(plot.flaggedMeaning, kLegendLine).size()) : 0);
    for (size_t k = 0; k < series.size(); ++k) {
        if (long(k) + 1 >= room && long(series.size()) > room) {
            entry("", "... and " + std::to_string(series.size() - k) + " more (hover a point)");
            break;
        }
        entry("<circle cx=\"" + printed("%.1f", legendX + 6) + "\" cy=\"" + printed("%.1f", y) +
                  "\" r=\"5\" fill=\"" + colourOf(series[k]) + "\"/>\n",
              series[k]);
    }
    if (anyFlagged)
        entry("<circle cx=\"" + printed("%.1f", legendX + 6) + "\" cy=\"" + printed("%.1f", y) +
                  "\" r=\"5\" fill=\"white\" stroke=\"#d62728\" stroke-width=\"2\"/>\n",
              plot.flaggedMeaning);
    if (!front.empty())
        entry("<line x1=\"" + printed("%.1f", legendX) + "\" y1=\"" + printed("%.1f", y) +
                  "\" x2=\"" + printed("%.1f", legendX + 14) + "\" y2=\"" + printed("%.1f", y) +
                  "\" stroke=\"#999\" stroke-dasharray=\"4 3\"/>\n",
              "Pareto front");
    s << "</g>\n</svg>\n";
    return s.str();
}

std::string colourScaleSvg(const HeatScale& scale, const std::string& label) {
    constexpr double W = kColourScaleWidth, H = 46, x0 = 18, x1 = W - 10, barTop = 4,
                     barHeight = 12;
    constexpr int steps = 60;
    std::ostringstream s;
    s << "<svg class=\"scale\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\""
      << H << "\" viewBox=\"0 0 " << W << " " << H
      << "\" font-family=\"sans-serif\" font-size=\"10\">\n";
    s << "<title>" << xml(label) << "</title>\n";
    const double step = (x1 - x0) / steps;
    for (int k = 0; k < steps; ++k)
        s << "<rect x=\"" << printed("%.2f", x0 + step * k) << "\" y=\"" << barTop << "\" width=\""
          << printed("%.2f", step + 0.3) << "\" height=\"" << barHeight << "\" fill=\""
          << hexColour(heatColour((k + 0.5) / steps)) << "\"/>\n";
    s << "<rect x=\"" << x0 << "\" y=\"" << barTop << "\" width=\"" << x1 - x0 << "\" height=\""
      << barHeight << "\" fill=\"none\" stroke=\"#444\"/>\n";
    const int first = int(std::lround(std::log10(scale.lo))),
              last = int(std::lround(std::log10(scale.hi)));
    for (int d = first; d <= last; ++d) {
        const double x =
            x0 + heatPosition(scale, std::pow(10.0, d) * (d == first ? 1.000001 : 1)) * (x1 - x0);
        s << "<line x1=\"" << printed("%.1f", x) << "\" y1=\"" << barTop + barHeight << "\" x2=\""
          << printed("%.1f", x) << "\" y2=\"" << barTop + barHeight + 4
          << "\" stroke=\"#444\"/>\n<text x=\"" << printed("%.1f", x) << "\" y=\""
          << barTop + barHeight + 13 << "\" text-anchor=\"middle\">" << (d == first ? "\u2264" : "")
          << decadeLabel(d) << "</text>\n";
    }
    s << "<text x=\"" << W / 2 << "\" y=\"" << H - 3 << "\" text-anchor=\"middle\">" << xml(label)
      << "</text>\n</svg>\n";
    return s.str();
}

std::string base64(const std::string& bytes) {
    static constexpr char kDigits[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (size_t i = 0; i < bytes.size(); i += 3) {
        const size_t n = std::min<size_t>(3, bytes.size() - i);
        std::uint32_t v = 0;
        for (size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? std::uint8_t(bytes[i + k]) : 0u);
        for (size_t k = 0; k < 4; ++k) out += k <= n ? kDigits[(v >> (18 - 6 * k)) & 63] : '=';
    }
    return out;
}

std::string toHtml(const Report& report) {
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n<title>"
      << xml(report.title) << "</title>\n<style>\n"
      << "body { font-family: sans-serif; margin: 2em; color: #222; }\n"
      << "table { border-collapse: collapse; font-size: 13px; }\n"
      << "th, td { border: 1px solid #ccc; padding: 2px 6px; text-align: right; }\n"
      << "th { background: #f0f0f0; } td.text { text-align: left; }\n"
      << ".plots { display: flex; flex-wrap: wrap; gap: 12px; margin-top: 1em; }\n"
      << ".groups { display: flex; flex-wrap: wrap; gap: 14px; }\n"
      << ".group { border: 1px solid #ccc; padding: 6px 8px; }\n"
      << ".group h3 { margin: 0 0 2px 0; font-size: 14px; }\n"
      << ".note { margin: 0 0 6px 0; font-size: 12px; color: #555; }\n"
      << ".figures { display: flex; flex-wrap: wrap; gap: 8px; align-items: flex-start; }\n"
      << "figure { margin: 0; } figcaption { font-size: 12px; }\n"
      << "figure img { display: block; image-rendering: pixelated; border: 1px solid #888; }\n"
      << ".legend { margin: 0.5em 0 1em 0; font-size: 13px; }\n"
      << ".legend .entry { margin-right: 18px; white-space: nowrap; }\n"
      << ".swatch { display: inline-block; width: 12px; height: 12px; border: 1px solid #444; "
         "margin-right: 5px; vertical-align: middle; }\n"
      << "</style>\n</head>\n<body>\n<h1>" << xml(report.title) << "</h1>\n";
    for (const std::string& p : report.paragraphs) h << "<p>" << xml(p) << "</p>\n";
    h << "<table>\n<tr>";
    for (const std::string& c : report.table.columns) h << "<th>" << xml(c) << "</th>";
    h << "</tr>\n";
    for (const auto& row : report.table.rows) {
        h << "<tr>";
        for (const ReportValue& v : row)
            h << (v.kind == ReportValue::Text ? "<td class=\"text\">" : "<td>") << xml(shortText(v))
              << "</td>";
        h << "</tr>\n";
    }
    h << "</table>\n<div class=\"plots\">\n";
    for (const Plot& plot : report.plots) h << "<div>\n" << toSvg(plot) << "</div>\n";
    h << "</div>\n";
    for (const Gallery& gallery : report.galleries) h << galleryHtml(gallery);
    h << "</body>\n</html>\n";
    return h.str();
}

void writeReportFiles(const Report& report, const std::string& directory, const std::string& stem,
                      std::ostream& out) {
    namespace fs = std::filesystem;
    std::error_code ec;
    fs::create_directories(directory, ec);
    if (ec || !fs::is_directory(directory))
        throw Error("--out " + directory + ": cannot create the folder (" + ec.message() + ")");
    const std::string base = (fs::path(directory) / stem).string();
    writeFileAtomically(base + ".csv", toCsv(report.table));
    writeFileAtomically(base + ".json", toJson(report));
    writeFileAtomically(base + ".html", toHtml(report));
    out << "wrote " << base << ".csv, " << base << ".json, " << base << ".html\n";
}

}  // namespace vkray::numerics
