// The outputs of `vkray stress` and `vkray report`: one table printed as
// text and written as CSV and JSON, and a self-contained HTML page with the
// table, inline SVG plots of error against run time (log-log, one point
// per configuration, the Pareto front drawn through the points no other
// point beats in both time and error, a legend on each) and galleries of
// pictures (PNG embedded as data: URIs; heat maps with their colour scale).
#pragma once

#include "image/pictures.h"

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace vkray::numerics {

// One cell: a number (written in full in CSV/JSON, to 3 digits in the text
// table), a whole number, or text. An empty cell is null in JSON.
struct ReportValue {
    enum Kind { Empty, Number, Integer, Text } kind = Empty;
    double number = 0;
    long long integer = 0;
    std::string text;

    static ReportValue num(double v) { return {Number, v, 0, {}}; }
    static ReportValue whole(long long v) { return {Integer, 0, v, {}}; }
    static ReportValue str(std::string s) { return {Text, 0, 0, std::move(s)}; }
};

struct ReportTable {
    std::vector<std::string> columns;
    std::vector<std::vector<ReportValue>> rows;  // each as long as columns
};

struct PlotPoint {
    std::string label;
    double x = 0, y = 0;   // y <= 0 is drawn on a "0" line below the lowest decade
    bool flagged = false;  // drawn hollow and red (e.g. a mode with hit/miss flips)
    std::string series;    // points of one series share a colour and a legend line
                           // (empty: the label is the series)
};

struct Plot {
    std::string title;
    std::string xLabel, yLabel;
    std::vector<PlotPoint> points;
    std::string flaggedMeaning = "flagged";  // the legend's line for hollow red points
};

// A picture in the page. A heat map carries its scale, drawn under it as a
// colour bar labelled `scaleLabel`.
struct Figure {
    std::string caption;
    std::string png;  // the PNG file's bytes
    std::optional<HeatScale> scale;
    std::string scaleLabel;
};

// Pictures shown together: one configuration, one stress case.
struct FigureGroup {
    std::string title;
    std::string note;
    std::vector<Figure> figures;
};

// A colour its pictures use and what it marks.
struct LegendEntry {
    std::string colour;  // "#rrggbb"
    std::string text;
};

struct Gallery {
    std::string title;
    std::vector<std::string> paragraphs;
    std::vector<LegendEntry> legend;
    std::vector<FigureGroup> groups;
};

struct Report {
    std::string title;
    std::vector<std::string> paragraphs;  // shown above the table (HTML) / in JSON "notes"
    ReportTable table;
    std::vector<Plot> plots;
    std::vector<Gallery> galleries;  // HTML only, after the plots
};

std::string formatTable(const ReportTable& table);
std::string toCsv(const ReportTable& table);
std::string toJson(const Report& report);
std::string toSvg(const Plot& plot);
std::string toHtml(const Report& report);

// A horizontal colour bar for a heat scale, ticks at each decade, as SVG.
std::string colourScaleSvg(const HeatScale& scale, const std::string& label);

// RFC 4648 base64 (with padding), for data: URIs.
std::string base64(const std::string& bytes);

// Writes DIR/STEM.csv, DIR/STEM.json and DIR/STEM.html (each atomically) and
// prints a line per file to `out`. Creates DIR if missing.
void writeReportFiles(const Report& report, const std::string& directory, const std::string& stem,
                      std::ostream& out);

}  // namespace vkray::numerics
