// SPDX-License-Identifier: MIT
// A small software rasteriser: deterministic, headless by construction, and with no graphics stack
// to install. Triangles fill a buffer of surface samples (position, normal, colour) at the
// supersampled resolution; lighting and shadows are then computed once per sample.
#include <impulse/viz/raster.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace impulse::viz
{
namespace
{

struct ViewVertex
{
    Vec3 view;  ///< camera frame: x right, y up, the camera looks along -z
    Vec3 world; ///< for lighting
    Vec3 normal;
    Vec3 colour;
};

struct ScreenVertex
{
    Real x = 0.0;
    Real y = 0.0;
    Real invDepth = 0.0; ///< 1 / distance along the view axis: affine in screen space
    const ViewVertex* source = nullptr;
};

/// Calls `plot(ix, iy, b0, b1, b2)` for every pixel centre inside the screen triangle, with its
/// barycentric coordinates.
template <class Plot>
void rasteriseTriangle(const Vec3& a, const Vec3& b, const Vec3& c, int width, int height, Plot&& plot)
{
    const Real area = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    if (std::abs(area) < 1e-12)
    {
        return;
    }
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}))));
    const int x1 = std::min(width - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}))));
    const int y1 = std::min(height - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}))));
    for (int iy = y0; iy <= y1; ++iy)
    {
        const Real py = iy + 0.5;
        for (int ix = x0; ix <= x1; ++ix)
        {
            const Real px = ix + 0.5;
            const Real w0 = ((b.x() - px) * (c.y() - py) - (b.y() - py) * (c.x() - px)) / area;
            const Real w1 = ((c.x() - px) * (a.y() - py) - (c.y() - py) * (a.x() - px)) / area;
            const Real w2 = 1.0 - w0 - w1;
            if (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0)
            {
                plot(ix, iy, w0, w1, w2);
            }
        }
    }
}

struct Basis
{
    Vec3 right;
    Vec3 up;
    Vec3 back;
};

Basis cameraBasis(const Camera& camera)
{
    const Vec3 back = (camera.eye - camera.target).normalized();
    Vec3 right = camera.up.cross(back);
    if (right.norm() < 1e-9)
    {
        right = Vec3::UnitX().cross(back).norm() > 1e-9 ? Vec3::UnitX().cross(back) : Vec3::UnitY().cross(back);
    }
    right.normalize();
    return {right, back.cross(right), back};
}

/// Surface samples of the supersampled picture.
struct SurfaceBuffer
{
    int width = 0;
    int height = 0;
    // single precision: a picture needs no more, and a frame's buffers stay a few tens of MB
    std::vector<float> invDepth; ///< 0: nothing drawn (sky)
    std::vector<Eigen::Vector3f> world;
    std::vector<Eigen::Vector3f> normal;
    std::vector<Eigen::Vector3f> colour;
};

/// Depths toward the light over the shadow region, orthographic.
struct ShadowMap
{
    static constexpr int size = 1024;
    Vec3 centre;
    Real radius = 1.0;
    Vec3 u, v, toLight;
    std::vector<Real> nearest = std::vector<Real>(static_cast<std::size_t>(size) * size, -INFINITY);

    Vec3 toMap(const Vec3& p) const
    {
        const Vec3 d = p - centre;
        return {(d.dot(u) / radius + 1.0) * 0.5 * size, (d.dot(v) / radius + 1.0) * 0.5 * size, d.dot(toLight)};
    }

    /// Fraction of a 3x3 neighbourhood that sees the light: soft shadow edges.
    Real lit(const Vec3& p) const
    {
        const Vec3 m = toMap(p);
        const Real bias = 4.0 * radius / size;
        int seen = 0;
        for (int dy = -1; dy <= 1; ++dy)
        {
            for (int dx = -1; dx <= 1; ++dx)
            {
                const int x = static_cast<int>(std::floor(m.x())) + dx;
                const int y = static_cast<int>(std::floor(m.y())) + dy;
                if (x < 0 || y < 0 || x >= size || y >= size ||
                    m.z() >= nearest[static_cast<std::size_t>(y) * size + x] - bias)
                {
                    ++seen;
                }
            }
        }
        return seen / 9.0;
    }
};

Vec3 toVec(Rgb c)
{
    return {c.r, c.g, c.b};
}

} // namespace

Camera frameCamera(const Bounds& bounds, const Vec3& up, Real aspect)
{
    const Vec3 u = up.normalized();
    Vec3 e1 = Vec3::UnitX() - Vec3::UnitX().dot(u) * u;
    if (e1.norm() < 1e-6)
    {
        e1 = Vec3::UnitY() - Vec3::UnitY().dot(u) * u;
    }
    e1.normalize();
    const Vec3 e2 = u.cross(e1);
    // front right and above: motion along x reads left to right, heights read upward; content that
    // stays near one level (rolling, gliding) is seen from higher up, so its paths open out
    const Vec3 extent = bounds.max - bounds.min;
    const Real vertical = std::abs(extent.dot(u));
    const Real horizontal = (extent - extent.dot(u) * u).norm();
    const Real azimuth = -65.0 * std::numbers::pi / 180.0;
    const Real elevation = (vertical < 0.25 * horizontal ? 40.0 : 22.0) * std::numbers::pi / 180.0;
    const Vec3 direction =
        std::cos(elevation) * (std::cos(azimuth) * e1 + std::sin(azimuth) * e2) + std::sin(elevation) * u;
    return frameCamera(bounds, up, aspect, direction);
}

Camera frameCamera(const Bounds& bounds, const Vec3& up, Real aspect, const Vec3& direction)
{
    Camera camera;
    camera.up = up.normalized();
    Vec3 from = direction.normalized();
    if (std::abs(from.dot(camera.up)) > 0.999)
    {
        // straight along up, the picture would have no up: tilt the view a little towards -y
        const Vec3 side = Vec3::UnitY() - Vec3::UnitY().dot(camera.up) * camera.up;
        from = (from - 0.05 * (side.norm() > 1e-6 ? side.normalized() : Vec3(Vec3::UnitX()))).normalized();
    }
    camera.target = bounds.centre();
    const Real radius = std::max(bounds.radius(), 0.05);
    const Real halfY = 0.5 * camera.fovYDegrees * std::numbers::pi / 180.0;
    const Real halfX = std::atan(aspect * std::tan(halfY));
    // far enough for the bounding sphere; then as close as the eight corners of the box allow, so
    // that long thin content (a rolling ball's path) fills the picture
    const Real sphereDistance = 1.05 * radius / std::sin(std::min(halfX, halfY));
    const Vec3 back = from;
    const Vec3 right = camera.up.cross(back).normalized();
    const Vec3 upInView = back.cross(right);
    auto fits = [&](Real distance)
    {
        const Vec3 eye = camera.target + distance * back;
        for (int corner = 0; corner < 8; ++corner)
        {
            const Vec3 p((corner & 1) ? bounds.max.x() : bounds.min.x(), (corner & 2) ? bounds.max.y() : bounds.min.y(),
                         (corner & 4) ? bounds.max.z() : bounds.min.z());
            const Vec3 d = p - eye;
            const Real depth = -d.dot(back);
            if (depth <= 0.0 || std::abs(d.dot(right)) > 0.9 * depth * std::tan(halfX) ||
                std::abs(d.dot(upInView)) > 0.9 * depth * std::tan(halfY))
            {
                return false;
            }
        }
        return true;
    };
    Real low = 0.0;
    Real high = sphereDistance;
    for (int i = 0; i < 40 && fits(high); ++i)
    {
        const Real middle = 0.5 * (low + high);
        (fits(middle) ? high : low) = middle;
    }
    camera.eye = camera.target + high * back;
    return camera;
}

Image renderImage(const std::vector<DrawnMesh>& meshes, const std::vector<Polyline>& lines, const Camera& camera,
                  const RenderSettings& settings)
{
    const int ss = std::max(1, settings.supersample);
    SurfaceBuffer buffer;
    buffer.width = settings.width * ss;
    buffer.height = settings.height * ss;
    const auto pixels = static_cast<std::size_t>(buffer.width) * buffer.height;
    buffer.invDepth.assign(pixels, 0.0f);
    buffer.world.resize(pixels);
    buffer.normal.resize(pixels);
    buffer.colour.resize(pixels);

    const Basis basis = cameraBasis(camera);
    const Real focal = 1.0 / std::tan(0.5 * camera.fovYDegrees * std::numbers::pi / 180.0);
    const Real aspect = static_cast<Real>(buffer.width) / buffer.height;
    const Real near = 1e-3 * (camera.eye - camera.target).norm();
    auto toView = [&](const Vec3& p)
    {
        const Vec3 d = p - camera.eye;
        return Vec3(d.dot(basis.right), d.dot(basis.up), d.dot(basis.back));
    };
    auto toScreen = [&](const Vec3& view)
    {
        const Real depth = -view.z();
        return Vec3((focal / aspect * view.x() / depth + 1.0) * 0.5 * buffer.width,
                    (1.0 - focal * view.y() / depth) * 0.5 * buffer.height, 1.0 / depth);
    };

    // ---- surfaces ----
    auto drawClipped = [&](const ViewVertex& a, const ViewVertex& b, const ViewVertex& c)
    {
        const Vec3 sa = toScreen(a.view), sb = toScreen(b.view), sc = toScreen(c.view);
        rasteriseTriangle(sa, sb, sc, buffer.width, buffer.height,
                          [&](int ix, int iy, Real w0, Real w1, Real w2)
                          {
                              const Real invDepth = w0 * sa.z() + w1 * sb.z() + w2 * sc.z();
                              const std::size_t i = static_cast<std::size_t>(iy) * buffer.width + ix;
                              if (static_cast<float>(invDepth) <= buffer.invDepth[i])
                              {
                                  return;
                              }
                              // perspective-correct weights
                              const Real p0 = w0 * sa.z() / invDepth, p1 = w1 * sb.z() / invDepth,
                                         p2 = w2 * sc.z() / invDepth;
                              buffer.invDepth[i] = static_cast<float>(invDepth);
                              buffer.world[i] = (p0 * a.world + p1 * b.world + p2 * c.world).cast<float>();
                              buffer.normal[i] = (p0 * a.normal + p1 * b.normal + p2 * c.normal).cast<float>();
                              buffer.colour[i] = (p0 * a.colour + p1 * b.colour + p2 * c.colour).cast<float>();
                          });
    };
    auto lerp = [](const ViewVertex& a, const ViewVertex& b, Real t)
    {
        return ViewVertex{a.view + t * (b.view - a.view), a.world + t * (b.world - a.world),
                          a.normal + t * (b.normal - a.normal), a.colour + t * (b.colour - a.colour)};
    };
    for (const DrawnMesh& drawn : meshes)
    {
        const TriangleMesh& mesh = *drawn.mesh;
        for (const auto& triangle : mesh.triangles)
        {
            ViewVertex corners[3];
            for (int k = 0; k < 3; ++k)
            {
                const std::uint32_t v = triangle[k];
                const Vec3 world = drawn.pose.toWorld(mesh.positions[v]);
                corners[k] = {toView(world), world, drawn.pose.rotation * mesh.normals[v], toVec(mesh.colours[v])};
            }
            // clip against the near plane z = -near (Sutherland-Hodgman, one plane)
            ViewVertex polygon[4];
            int count = 0;
            for (int k = 0; k < 3; ++k)
            {
                const ViewVertex& current = corners[k];
                const ViewVertex& next = corners[(k + 1) % 3];
                const Real dc = -current.view.z() - near;
                const Real dn = -next.view.z() - near;
                if (dc >= 0.0)
                {
                    polygon[count++] = current;
                }
                if ((dc >= 0.0) != (dn >= 0.0))
                {
                    polygon[count++] = lerp(current, next, dc / (dc - dn));
                }
            }
            for (int k = 1; k + 1 < count; ++k)
            {
                drawClipped(polygon[0], polygon[k], polygon[k + 1]);
            }
        }
    }

    // ---- light and shadows ----
    const Vec3 sceneUp = camera.up.normalized();
    // nearly overhead, so a shadow sits under its body and tells its height
    const Vec3 toLight = (3.5 * sceneUp - 0.6 * basis.right + 0.4 * basis.back).normalized();
    ShadowMap shadow;
    if (settings.shadows)
    {
        shadow.centre = settings.shadowBounds.centre();
        shadow.radius = std::max(settings.shadowBounds.radius(), 1e-3) * 1.2;
        shadow.toLight = toLight;
        shadow.u = basis.right - basis.right.dot(toLight) * toLight;
        shadow.u.normalize();
        shadow.v = toLight.cross(shadow.u);
        for (const DrawnMesh& drawn : meshes)
        {
            if (!drawn.castsShadow)
            {
                continue;
            }
            for (const auto& triangle : drawn.mesh->triangles)
            {
                const Vec3 a = shadow.toMap(drawn.pose.toWorld(drawn.mesh->positions[triangle[0]]));
                const Vec3 b = shadow.toMap(drawn.pose.toWorld(drawn.mesh->positions[triangle[1]]));
                const Vec3 c = shadow.toMap(drawn.pose.toWorld(drawn.mesh->positions[triangle[2]]));
                rasteriseTriangle(a, b, c, ShadowMap::size, ShadowMap::size,
                                  [&](int ix, int iy, Real w0, Real w1, Real w2)
                                  {
                                      Real& nearest =
                                          shadow.nearest[static_cast<std::size_t>(iy) * ShadowMap::size + ix];
                                      nearest = std::max(nearest, w0 * a.z() + w1 * b.z() + w2 * c.z());
                                  });
            }
        }
    }

    const Vec3 skyTop(0.55, 0.70, 0.88);
    const Vec3 horizon(0.90, 0.93, 0.96);
    const Real fadeStart = 2.5 * std::max(settings.shadowBounds.radius(), 0.05);
    std::vector<Eigen::Vector3f> shaded(pixels);
    for (int iy = 0; iy < buffer.height; ++iy)
    {
        const Real skyBlend = static_cast<Real>(iy) / buffer.height;
        const Vec3 sky = skyTop + skyBlend * (horizon - skyTop);
        for (int ix = 0; ix < buffer.width; ++ix)
        {
            const std::size_t i = static_cast<std::size_t>(iy) * buffer.width + ix;
            if (buffer.invDepth[i] == 0.0f)
            {
                shaded[i] = sky.cast<float>();
                continue;
            }
            const Vec3 p = buffer.world[i].cast<Real>();
            Vec3 n = buffer.normal[i].cast<Real>().normalized();
            const Vec3 toEye = (camera.eye - p).normalized();
            if (n.dot(toEye) < 0.0)
            {
                n = -n; // two-sided: a plane seen from below, an open mesh
            }
            const Real light = settings.shadows ? shadow.lit(p) : 1.0;
            const Real diffuse = std::max(0.0, n.dot(toLight)) * light;
            const Real skyLight = 0.5 + 0.5 * n.dot(sceneUp);
            const Vec3 halfway = (toLight + toEye).normalized();
            // shininess 48 by squaring (x^48 = x^32 x^16): std::pow was a fifth of a frame's time
            const Real x1 = std::max(0.0, n.dot(halfway));
            const Real x2 = x1 * x1, x4 = x2 * x2, x8 = x4 * x4, x16 = x8 * x8;
            const Real specular = 0.25 * x16 * x16 * x16 * light;
            Vec3 colour =
                buffer.colour[i].cast<Real>() * (0.30 + 0.18 * skyLight + 0.62 * diffuse) + Vec3::Constant(specular);
            // far ground fades into the horizon, so the finite plane reads as an endless floor
            const Vec3 fromCentre = p - settings.shadowBounds.centre();
            const Real across = (fromCentre - fromCentre.dot(sceneUp) * sceneUp).norm();
            const Real fade = std::clamp((across - fadeStart) / (1.5 * fadeStart), 0.0, 1.0);
            shaded[i] = (colour + fade * (horizon - colour)).cast<float>();
        }
    }

    // ---- lines, hidden behind surfaces ----
    for (const Polyline& line : lines)
    {
        const Eigen::Vector3f colour = toVec(line.colour).cast<float>();
        const Real radius = 1.1 * ss;
        for (std::size_t k = 0; k + 1 < line.points.size(); ++k)
        {
            const Vec3 va = toView(line.points[k]);
            const Vec3 vb = toView(line.points[k + 1]);
            if (-va.z() < near || -vb.z() < near)
            {
                continue;
            }
            const Vec3 a = toScreen(va), b = toScreen(vb);
            const Real length = std::hypot(b.x() - a.x(), b.y() - a.y());
            const int steps = std::max(1, static_cast<int>(std::ceil(length / (0.5 * ss))));
            for (int s = 0; s <= steps; ++s)
            {
                const Vec3 p = a + (static_cast<Real>(s) / steps) * (b - a);
                const int r = static_cast<int>(std::ceil(radius));
                for (int dy = -r; dy <= r; ++dy)
                {
                    for (int dx = -r; dx <= r; ++dx)
                    {
                        const int ix = static_cast<int>(std::floor(p.x())) + dx;
                        const int iy = static_cast<int>(std::floor(p.y())) + dy;
                        if (ix < 0 || iy < 0 || ix >= buffer.width || iy >= buffer.height ||
                            std::hypot(ix + 0.5 - p.x(), iy + 0.5 - p.y()) > radius)
                        {
                            continue;
                        }
                        const std::size_t i = static_cast<std::size_t>(iy) * buffer.width + ix;
                        if (p.z() >= buffer.invDepth[i] * (1.0 - 1e-4))
                        {
                            shaded[i] = colour;
                        }
                    }
                }
            }
        }
    }

    // ---- average the supersamples ----
    Image image;
    image.width = settings.width;
    image.height = settings.height;
    image.rgb.resize(static_cast<std::size_t>(image.width) * image.height * 3);
    for (int y = 0; y < image.height; ++y)
    {
        for (int x = 0; x < image.width; ++x)
        {
            Eigen::Vector3f sum = Eigen::Vector3f::Zero();
            for (int sy = 0; sy < ss; ++sy)
            {
                for (int sx = 0; sx < ss; ++sx)
                {
                    sum += shaded[static_cast<std::size_t>(y * ss + sy) * buffer.width + x * ss + sx];
                }
            }
            sum /= static_cast<float>(ss * ss);
            for (int c = 0; c < 3; ++c)
            {
                image.rgb[(static_cast<std::size_t>(y) * image.width + x) * 3 + c] =
                    static_cast<std::uint8_t>(std::lround(std::clamp(sum[c], 0.0f, 1.0f) * 255.0f));
            }
        }
    }
    return image;
}

} // namespace impulse::viz
