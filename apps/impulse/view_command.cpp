// SPDX-License-Identifier: MIT
// The replay page: three.js from Debian's libjs-three package and the trajectory, inlined into one
// HTML file that needs no network.
#include "view_command.hpp"

#include "see_inputs.hpp"

#include <impulse/io/markup.hpp>
#include <impulse/viz/raster.hpp>
#include <impulse/viz/series.hpp>
#include <impulse/viz/tessellate.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

namespace impulse::app::assets
{
extern const char* const viewerHtml;
extern const char* const viewerJs;
} // namespace impulse::app::assets

namespace impulse::app
{
namespace
{

/// Compact JSON numbers: enough digits for the eye, few bytes for long runs.
class JsonWriter
{
  public:
    explicit JsonWriter(int digits) : m_digits(digits) {}
    JsonWriter& raw(const std::string& text)
    {
        m_out += text;
        return *this;
    }
    JsonWriter& number(double value)
    {
        char text[32];
        std::snprintf(text, sizeof text, "%.*g", m_digits, std::isfinite(value) ? value : 0.0);
        m_out += text;
        return *this;
    }
    /// A JSON string safe inside a <script> element: '<' is escaped so "</script>" cannot appear.
    JsonWriter& string(const std::string& text)
    {
        m_out += '"';
        for (const char c : text)
        {
            if (c == '"' || c == '\\')
            {
                m_out += '\\';
                m_out += c;
            }
            else if (c == '<' || static_cast<unsigned char>(c) < 0x20)
            {
                char escaped[8];
                std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned char>(c));
                m_out += escaped;
            }
            else
            {
                m_out += c;
            }
        }
        m_out += '"';
        return *this;
    }
    template <class Range, class Each> JsonWriter& array(const Range& range, Each&& each)
    {
        m_out += '[';
        bool first = true;
        for (const auto& item : range)
        {
            if (!first)
            {
                m_out += ',';
            }
            first = false;
            each(item);
        }
        m_out += ']';
        return *this;
    }
    const std::string& text() const { return m_out; }

  private:
    int m_digits;
    std::string m_out;
};

void writeMesh(JsonWriter& json, const viz::TriangleMesh& mesh)
{
    JsonWriter compact(4);
    auto vectors = [&](const std::vector<Vec3>& values) {
        compact.array(values,
                      [&](const Vec3& v) { compact.number(v.x()).raw(",").number(v.y()).raw(",").number(v.z()); });
    };
    compact.raw("{\"positions\":");
    vectors(mesh.positions);
    compact.raw(",\"normals\":");
    vectors(mesh.normals);
    compact.raw(",\"colours\":");
    compact.array(mesh.colours,
                  [&](const viz::Rgb& c) { compact.number(c.r).raw(",").number(c.g).raw(",").number(c.b); });
    compact.raw(",\"indices\":");
    compact.array(mesh.triangles,
                  [&](const auto& t) { compact.number(t[0]).raw(",").number(t[1]).raw(",").number(t[2]); });
    compact.raw("}");
    json.raw(compact.text());
}

void writePose(JsonWriter& json, const Vec3& position, const Quat& q)
{
    // three.js order: position, then quaternion x, y, z, w
    json.number(position.x()).raw(",").number(position.y()).raw(",").number(position.z()).raw(",");
    json.number(q.x()).raw(",").number(q.y()).raw(",").number(q.z()).raw(",").number(q.w());
}

std::string pageData(const LoadedRun& run)
{
    const io::Trajectory& trajectory = run.trajectory;
    const viz::Series series = viz::computeSeries(trajectory, run.view);
    const viz::Bounds bounds = viz::contentBounds(trajectory, run.view);
    const Vec3 up = viz::upDirection(run.view.gravity);

    // a long run is thinned to at most this many samples, always keeping the last
    constexpr std::size_t maxSamples = 4000;
    const std::size_t stride = (trajectory.sampleCount() + maxSamples - 1) / maxSamples;
    std::vector<std::size_t> kept;
    for (std::size_t i = 0; i < trajectory.sampleCount(); i += stride)
    {
        kept.push_back(i);
    }
    if (kept.back() != trajectory.sampleCount() - 1)
    {
        kept.push_back(trajectory.sampleCount() - 1);
    }

    JsonWriter json(7);
    json.raw("{\"title\":").string(run.title);
    json.raw(",\"up\":[").number(up.x()).raw(",").number(up.y()).raw(",").number(up.z()).raw("]");
    const Vec3 centre = bounds.centre();
    json.raw(",\"centre\":[").number(centre.x()).raw(",").number(centre.y()).raw(",").number(centre.z()).raw("]");
    json.raw(",\"radius\":").number(std::max(bounds.radius(), 0.05));
    const Vec3 eye = viz::frameCamera(bounds, up, 16.0 / 10.0).eye; // the browser window's shape is unknown
    json.raw(",\"eye\":[").number(eye.x()).raw(",").number(eye.y()).raw(",").number(eye.z()).raw("]");
    json.raw(",\"times\":").array(kept, [&](std::size_t i) { json.number(trajectory.times[i]); });

    json.raw(",\"bodies\":[");
    for (std::size_t k = 0; k < trajectory.bodyCount; ++k)
    {
        json.raw(k ? ",{" : "{");
        json.raw("\"name\":").string(run.view.names[k]);
        json.raw(",\"colour\":").string(viz::hexColour(viz::bodyColour(k)));
        json.raw(",\"mesh\":");
        writeMesh(json, run.view.dynamicTriangles(k));
        json.raw(",\"poses\":")
            .array(kept,
                   [&](std::size_t i)
                   {
                       const io::BodySample& s = trajectory.at(i, k);
                       writePose(json, s.position, s.orientation);
                   });
        json.raw("}");
    }
    json.raw("],\"statics\":[");
    bool first = true;
    for (const viz::StaticBody& body : run.view.staticBodies)
    {
        json.raw(first ? "{" : ",{");
        first = false;
        const viz::PlanePatch patch{body.pose.toLocal(bounds.centre()), 4.5 * std::max(bounds.radius(), 0.1)};
        json.raw("\"mesh\":");
        writeMesh(json, viz::bodyTriangles(body.shape, {0.7f, 0.7f, 0.72f}, patch));
        json.raw(",\"pose\":[");
        writePose(json, body.pose.position, body.pose.orientation);
        json.raw("]}");
    }
    json.raw("],\"series\":{\"energyLabel\":").string(series.energyLabel);
    auto perBody = [&](const std::vector<std::vector<Real>>& values)
    {
        json.array(values, [&](const std::vector<Real>& one)
                   { json.array(kept, [&](std::size_t i) { json.number(one[i]); }); });
    };
    json.raw(",\"height\":");
    perBody(series.height);
    json.raw(",\"speed\":");
    perBody(series.speed);
    json.raw(",\"energy\":").array(kept, [&](std::size_t i) { json.number(series.energy[i]); });
    json.raw("}}");
    return json.text();
}

std::optional<std::string> readText(const std::string& path)
{
    std::ifstream file(path, std::ios::binary);
    if (!file)
    {
        return std::nullopt;
    }
    std::ostringstream text;
    text << file.rdbuf();
    return text.str();
}

/// Replaces each @NAME@ of the template once, in one pass, so inserted text is never searched.
std::string fillTemplate(const std::string& page, const std::vector<std::pair<std::string, std::string>>& fields)
{
    std::string out;
    std::size_t position = 0;
    while (true)
    {
        const std::size_t open = page.find('@', position);
        if (open == std::string::npos)
        {
            break;
        }
        const std::size_t close = page.find('@', open + 1);
        const std::string name = close == std::string::npos ? "" : page.substr(open + 1, close - open - 1);
        const auto field = std::find_if(fields.begin(), fields.end(), [&](const auto& f) { return f.first == name; });
        if (field == fields.end())
        {
            out.append(page, position, open + 1 - position);
            position = open + 1;
            continue;
        }
        out.append(page, position, open - position);
        out += field->second;
        position = close + 1;
    }
    out.append(page, position);
    return out;
}

} // namespace

int writeViewer(const ViewOptions& options)
{
    LoadedRun run;
    try
    {
        run = loadRun(options.trajectoryPath, options.scenePath);
    }
    catch (const InputError& error)
    {
        std::cerr << "impulse: " << error.what() << "\n";
        return 2;
    }
    const std::string threePath = options.threeDirectory + "/three.min.js";
    const std::string orbitPath = options.threeDirectory + "/examples/js/controls/OrbitControls.js";
    const std::optional<std::string> three = readText(threePath);
    const std::optional<std::string> orbit = readText(orbitPath);
    if (!three || !orbit)
    {
        std::cerr << "impulse: " << (three ? orbitPath : threePath)
                  << ": cannot read three.js (Debian: apt-get install libjs-three, or give --three DIR)\n";
        return 1;
    }
    for (const std::string* script : {&*three, &*orbit})
    {
        if (script->find("</script") != std::string::npos)
        {
            std::cerr << "impulse: three.js contains \"</script\" and cannot be inlined\n";
            return 1;
        }
    }
    const std::string page = fillTemplate(assets::viewerHtml, {{"TITLE", io::escapeMarkup(run.title)},
                                                               {"DATA", pageData(run)},
                                                               {"THREE", *three},
                                                               {"ORBIT", *orbit},
                                                               {"VIEWER", assets::viewerJs}});
    const std::string outPath =
        options.outPath.empty() ? withExtension(options.trajectoryPath, ".html") : options.outPath;
    std::ofstream file(outPath, std::ios::binary);
    file << page;
    file.close();
    if (!file)
    {
        std::cerr << "impulse: " << outPath << ": cannot write\n";
        return 1;
    }
    std::printf("viewer      %s (%zu bodies, %zu samples, %.1f MB, works offline)\n", outPath.c_str(),
                run.trajectory.bodyCount, run.trajectory.sampleCount(), static_cast<double>(page.size()) / 1e6);
    return 0;
}

} // namespace impulse::app
