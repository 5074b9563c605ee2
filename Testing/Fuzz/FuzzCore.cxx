// A deterministic mutation fuzzer of the core's entry points: the functions the VTK adapters
// call (with the checks the adapters make first), fed with small valid inputs broken in the
// ways real files and scripts break them. A case passes when the entry point returns (an error
// or a result) and a result it calls good is finite and as claimed; it fails by crashing (ASan
// and UBSan report it), by running past the per-case time limit, or by a silent wrong answer.
// Written by hand: libFuzzer needs clang and byte-level inputs, while these inputs are
// structured (meshes, Diracs, options) and the mutations are the known ways they go wrong.
//
//   otparam_fuzz [--cases N] [--seed S] [--entry NAME] [--case K] [--case-seconds T] [--list]
//
// Every case is reproducible from (entry, seed, case number): `--entry E --seed S --case K`.
#include "Mesh/MeshFile.h"
#include "Pipeline/AreaPreservingPipeline.h"
#include "Pipeline/DiskStages.h"
#include "Pipeline/SphereStages.h"
#include "Transport/PlanarSource.h"

#include "OTTestProblems.h"
#include "RingDisk.h"
#include "SphereMeshes.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <mutex>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

using namespace otparam;

namespace
{
using Rng = std::mt19937_64;

// ---- What a case is doing, for the crash handler and the watchdog.
char CurrentCase[256] = "none";

void reportCrash(int signal)
{
  char line[400];
  const int n =
    std::snprintf(line, sizeof line, "\notparam_fuzz: signal %d in case %s\n", signal, CurrentCase);
  if (n > 0)
  {
    (void)!write(2, line, static_cast<size_t>(n));
  }
  if (signal != 0)
  {
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
}

// AddressSanitizer ends the process its own way: it calls this back first (when linked in).
extern "C" __attribute__((weak)) void __sanitizer_set_death_callback(void (*)(void));
void reportSanitizerDeath()
{
  reportCrash(0);
}

// Aborts the process when a case runs longer than the limit (a hang is a finding too).
class Watchdog
{
public:
  explicit Watchdog(double seconds)
    : Limit(seconds)
    , Thread([this] { this->watch(); })
  {
  }
  ~Watchdog()
  {
    {
      std::lock_guard<std::mutex> lock(this->Mutex);
      this->Stop = true;
    }
    this->Wake.notify_all();
    this->Thread.join();
  }
  void startCase()
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Started = std::chrono::steady_clock::now();
    ++this->Generation;
    this->Wake.notify_all();
  }

private:
  void watch()
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    while (!this->Stop)
    {
      const long long generation = this->Generation;
      const auto deadline = this->Started + std::chrono::duration<double>(this->Limit);
      if (this->Wake.wait_until(lock, deadline) == std::cv_status::timeout && !this->Stop &&
        generation == this->Generation && generation > 0)
      {
        std::fprintf(
          stderr, "\notparam_fuzz: HANG: case %s ran over %.0f s\n", CurrentCase, this->Limit);
        std::abort();
      }
    }
  }
  double Limit;
  std::mutex Mutex;
  std::condition_variable Wake;
  bool Stop = false;
  long long Generation = 0;
  std::chrono::steady_clock::time_point Started = std::chrono::steady_clock::now();
  std::thread Thread;
};

// ---- Numbers a mutation writes.
double hostileNumber(Rng& rng)
{
  const double values[] = { std::numeric_limits<double>::quiet_NaN(),
    std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), 0.0, -0.0,
    5e-324, 1e-310, -1e-300, 1e300, -1e300, 1e-15, 1.0 + 1e-15 };
  return values[rng() % (sizeof values / sizeof values[0])];
}

size_t pick(Rng& rng, size_t n)
{
  return n == 0 ? 0 : static_cast<size_t>(rng() % n);
}

// a + b wrapping around, as the hostile indices (near +-2^63) must not overflow in the driver.
std::int64_t wrapAdd(std::int64_t a, std::int64_t b)
{
  return static_cast<std::int64_t>(static_cast<std::uint64_t>(a) + static_cast<std::uint64_t>(b));
}

// True when the triangle's ids name points (an earlier mutation may have broken them).
bool inRange(const std::array<std::int64_t, 3>& triangle, size_t points)
{
  for (std::int64_t id : triangle)
  {
    if (id < 0 || static_cast<std::uint64_t>(id) >= points)
    {
      return false;
    }
  }
  return true;
}

// ---- Meshes: mutations of coordinates and of connectivity.
void mutateMesh(TriangleSoup& soup, Rng& rng)
{
  auto& p = soup.points;
  auto& t = soup.triangles;
  switch (rng() % 16)
  {
    case 0: // one coordinate NaN, inf, denormal, huge
      if (!p.empty())
      {
        double* c = &p[pick(rng, p.size())].x;
        c[pick(rng, 3)] = hostileNumber(rng);
      }
      break;
    case 1: // the whole surface scaled to the edge of double's range
    {
      const double s = (rng() % 2) ? 1e-300 : 1e300;
      for (Vec3& q : p)
      {
        q = s * q;
      }
      break;
    }
    case 2: // two points at the same place
      if (p.size() > 1)
      {
        p[pick(rng, p.size())] = p[pick(rng, p.size())];
      }
      break;
    case 3: // a triangle collapsed to a point
      if (!t.empty())
      {
        const auto tri = t[pick(rng, t.size())];
        if (inRange(tri, p.size()))
        {
          p[tri[1]] = p[tri[0]];
          p[tri[2]] = p[tri[0]];
        }
      }
      break;
    case 4: // every point on a line or a plane
    {
      const int axis = static_cast<int>(pick(rng, 3));
      for (Vec3& q : p)
      {
        (&q.x)[axis] = 0.0;
        if (rng() % 2)
        {
          (&q.x)[(axis + 1) % 3] = 0.0;
        }
      }
      break;
    }
    case 5: // an index out of range
      if (!t.empty())
      {
        const std::int64_t bad[] = { -1, static_cast<std::int64_t>(p.size()),
          std::numeric_limits<std::int64_t>::max(), std::numeric_limits<std::int64_t>::min() };
        t[pick(rng, t.size())][pick(rng, 3)] = bad[pick(rng, 4)];
      }
      break;
    case 6: // a triangle twice
      if (!t.empty())
      {
        t.push_back(t[pick(rng, t.size())]);
      }
      break;
    case 7: // a triangle turned over
      if (!t.empty())
      {
        auto& tri = t[pick(rng, t.size())];
        std::swap(tri[0], tri[1]);
      }
      break;
    case 8: // a triangle repeating a vertex
      if (!t.empty())
      {
        auto& tri = t[pick(rng, t.size())];
        tri[2] = tri[0];
      }
      break;
    case 9: // a fin: a third triangle on an edge
      if (!t.empty())
      {
        const auto tri = t[pick(rng, t.size())];
        if (inRange(tri, p.size()))
        {
          p.push_back(p[tri[0]] + Vec3{ 0.0, 0.0, 0.3 });
          t.push_back({ tri[0], tri[1], static_cast<std::int64_t>(p.size()) - 1 });
        }
      }
      break;
    case 10: // triangles removed: holes, several components, isolated points
    {
      const size_t remove = 1 + pick(rng, std::max<size_t>(1, t.size() / 3));
      for (size_t k = 0; k < remove && !t.empty(); ++k)
      {
        t.erase(t.begin() + static_cast<std::ptrdiff_t>(pick(rng, t.size())));
      }
      break;
    }
    case 11: // nothing left
      if (rng() % 2)
      {
        t.clear();
      }
      else
      {
        p.clear();
      }
      break;
    case 12: // a point pulled far away (long thin triangles)
      if (!p.empty())
      {
        p[pick(rng, p.size())] = 1e6 * p[pick(rng, p.size())];
      }
      break;
    case 13: // a second copy of the surface: two components
    {
      const std::int64_t offset = static_cast<std::int64_t>(p.size());
      const size_t triangles = t.size();
      for (size_t k = 0, n = p.size(); k < n; ++k)
      {
        p.push_back(p[k] + Vec3{ 5.0, 0.0, 0.0 });
      }
      for (size_t k = 0; k < triangles; ++k)
      {
        t.push_back(
          { wrapAdd(t[k][0], offset), wrapAdd(t[k][1], offset), wrapAdd(t[k][2], offset) });
      }
      break;
    }
    case 14: // tiny noise on every point
      for (Vec3& q : p)
      {
        q.x += 1e-13 * (static_cast<double>(rng() % 2001) - 1000.0);
      }
      break;
    default: // every triangle turned over
      for (auto& tri : t)
      {
        std::swap(tri[1], tri[2]);
      }
      break;
  }
}

// ---- Per-item values (masses, densities): zero, negative, non-finite, wrong count, contrast.
void mutateValues(std::vector<double>& v, Rng& rng)
{
  switch (rng() % 6)
  {
    case 0:
      if (!v.empty())
      {
        v[pick(rng, v.size())] = hostileNumber(rng);
      }
      break;
    case 1:
      if (!v.empty())
      {
        v.pop_back();
      }
      break;
    case 2:
      v.push_back(1.0);
      break;
    case 3:
      for (double& x : v)
      {
        x = 0.0;
      }
      break;
    case 4: // a contrast of 1e300
      if (!v.empty())
      {
        v[pick(rng, v.size())] *= 1e300;
      }
      break;
    default:
      if (!v.empty())
      {
        v[pick(rng, v.size())] = -v[pick(rng, v.size())];
      }
      break;
  }
}

void mutatePoints2(std::vector<Vec2>& y, Rng& rng)
{
  if (y.empty())
  {
    return;
  }
  switch (rng() % 4)
  {
    case 0:
      (&y[pick(rng, y.size())].x)[pick(rng, 2)] = hostileNumber(rng);
      break;
    case 1:
      y[pick(rng, y.size())] = y[pick(rng, y.size())];
      break;
    case 2: // all on a line
      for (Vec2& q : y)
      {
        q.y = 0.5 * q.x;
      }
      break;
    default:
      y.resize(pick(rng, 4));
      break;
  }
}

void mutatePoints3(std::vector<Vec3>& y, Rng& rng)
{
  if (y.empty())
  {
    return;
  }
  switch (rng() % 5)
  {
    case 0:
      (&y[pick(rng, y.size())].x)[pick(rng, 3)] = hostileNumber(rng);
      break;
    case 1:
      y[pick(rng, y.size())] = y[pick(rng, y.size())];
      break;
    case 2: // all in one hemisphere
      for (Vec3& q : y)
      {
        q.z = std::abs(q.z);
      }
      break;
    case 3: // off the sphere
      y[pick(rng, y.size())] = 1.5 * y[pick(rng, y.size())];
      break;
    default:
      y.resize(pick(rng, 5));
      break;
  }
}

// ---- Options at and beyond their bounds.
void mutateSampler(SamplerOptions& o, Rng& rng)
{
  const long long counts[] = { -5, 0, 1, 2, 3, 4, 7, 20000 };
  switch (rng() % 4)
  {
    case 0:
      o.numberOfSamples = counts[pick(rng, 8)];
      break;
    case 1:
      o.minimumAngleDegrees = std::vector<double>{ -1.0, 0.0, 1.0, 29.9, 30.0, 30.1, 33.0, 60.0,
        90.0, std::numeric_limits<double>::quiet_NaN() }[pick(rng, 10)];
      break;
    case 2:
      o.mode = static_cast<SamplingMode>(pick(rng, 4));
      break;
    default:
      o.maximumNumberOfSamples = counts[pick(rng, 8)];
      break;
  }
}

void mutateTransport(OTOptions& o, Rng& rng)
{
  switch (rng() % 3)
  {
    case 0:
      o.tolerance = std::vector<double>{ 0.0, -1.0, 1.0, 1e-300, 1e-17,
        std::numeric_limits<double>::quiet_NaN() }[pick(rng, 6)];
      break;
    case 1:
      o.maximumNumberOfIterations = std::vector<int>{ -1, 0, 1, 2 }[pick(rng, 4)];
      break;
    default:
      o.coarseToFineStart = !o.coarseToFineStart;
      break;
  }
}

// ---- Base inputs: small and valid, so that each mutation is what breaks them.
TriangleSoup diskSurface(Rng& rng)
{
  const otparam::testing::PlanarMesh disk =
    otparam::testing::makePlanarDisk(4 + static_cast<int>(pick(rng, 8)));
  TriangleSoup soup;
  for (Vec2 q : disk.points)
  {
    soup.points.push_back({ q.x, q.y, 0.4 * std::exp(-4.0 * dot(q, q)) });
  }
  for (const Triangle& t : disk.triangles)
  {
    soup.triangles.push_back({ t[0], t[1], t[2] });
  }
  return soup;
}

TriangleSoup sphereSurface(Rng& rng)
{
  const SurfaceMesh hull = otparam::testing::convexHullMesh(
    otparam::testing::fibonacciSphere(40 + static_cast<int>(pick(rng, 200))));
  TriangleSoup soup;
  for (Vec3 q : hull.points)
  {
    soup.points.push_back({ q.x * 2.0, q.y, q.z * (1.0 + 0.3 * q.x) }); // not round
  }
  for (const Triangle& t : hull.triangles)
  {
    soup.triangles.push_back({ t[0], t[1], t[2] });
  }
  return soup;
}

std::string offText(const TriangleSoup& soup)
{
  std::ostringstream s;
  s.precision(17);
  s << "OFF\n" << soup.points.size() << ' ' << soup.triangles.size() << " 0\n";
  for (Vec3 q : soup.points)
  {
    s << q.x << ' ' << q.y << ' ' << q.z << '\n';
  }
  for (const auto& t : soup.triangles)
  {
    s << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  }
  return s.str();
}

std::string objText(const TriangleSoup& soup)
{
  std::ostringstream s;
  s.precision(17);
  for (Vec3 q : soup.points)
  {
    s << "v " << q.x << ' ' << q.y << ' ' << q.z << '\n';
  }
  for (const auto& t : soup.triangles)
  {
    s << "f " << wrapAdd(t[0], 1) << '/' << wrapAdd(t[0], 1) << ' ' << wrapAdd(t[1], 1) << "//"
      << wrapAdd(t[1], 1) << ' ' << wrapAdd(t[2], -static_cast<std::int64_t>(soup.points.size()))
      << '\n';
  }
  return s.str();
}

// Byte-level damage to a file's text.
void mutateText(std::string& text, Rng& rng)
{
  if (text.empty())
  {
    text = "\x7f"
           "ELF";
    return;
  }
  const size_t at = pick(rng, text.size());
  switch (rng() % 7)
  {
    case 0:
      text.resize(at); // truncated
      break;
    case 1:
      text[at] = static_cast<char>(rng() % 256);
      break;
    case 2:
      text.insert(at,
        std::vector<std::string>{ "nan", "inf", "-", "1e999", "\r\n", "#", "\0",
          "99999999999999999999", " / ", "0" }[pick(rng, 10)]);
      break;
    case 3:
      text.erase(at, pick(rng, 20));
      break;
    case 4:
      text.insert(at, text.substr(pick(rng, text.size()), pick(rng, 40)));
      break;
    case 5:
      text.replace(at, 1, "\n");
      break;
    default:
      for (char& c : text)
      {
        c = c == '\n' ? ' ' : c; // one line
      }
      break;
  }
}

// ---- Checks of what an entry point calls a success.
bool finite(const std::vector<Vec2>& v)
{
  for (Vec2 q : v)
  {
    if (!std::isfinite(q.x) || !std::isfinite(q.y))
    {
      return false;
    }
  }
  return true;
}

bool finite(const std::vector<Vec3>& v)
{
  for (Vec3 q : v)
  {
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
    {
      return false;
    }
  }
  return true;
}

bool finite(const std::vector<double>& v)
{
  for (double x : v)
  {
    if (!std::isfinite(x))
    {
      return false;
    }
  }
  return true;
}

bool mentions(const Status& status, const char* word)
{
  for (const std::string& w : status.warnings)
  {
    if (w.find(word) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

// What a case found: "" (it returned, and a result it called good is finite and as claimed),
// or what is wrong.
using CaseResult = std::string;

// Set by a case whose entry point accepted the input (returned a result it calls good).
bool Accepted = false;
// The message of a case refused or failed cleanly (printed with --verbose, to read them).
std::string Refusal;

CaseResult refused(const std::string& message)
{
  Refusal = message;
  return "";
}
CaseResult refused(const Status& status)
{
  return refused(status.aborted ? "aborted" : status.error);
}

// ---- The entry points.
CaseResult fuzzReader(Rng& rng, bool obj)
{
  TriangleSoup soup = diskSurface(rng);
  if (rng() % 2)
  {
    mutateMesh(soup, rng);
  }
  std::string text = obj ? objText(soup) : offText(soup);
  for (int k = static_cast<int>(pick(rng, 4)); k > 0; --k) // 0 to 3 mutations
  {
    mutateText(text, rng);
  }
  if (const char* dump = std::getenv("OTPARAM_FUZZ_DUMP"))
  {
    std::ofstream(dump) << text;
  }
  std::istringstream in(text);
  MeshFileData data;
  const std::string error = obj ? readOBJ(in, data) : readOFF(in, data);
  if (!error.empty())
  {
    return refused(error);
  }
  Accepted = true;
  for (const Triangle& t : data.triangles)
  {
    for (int i : t)
    {
      if (i < 0 || static_cast<size_t>(i) >= data.points.size())
      {
        return "a triangle with a vertex id out of range was accepted";
      }
    }
  }
  return finite(data.points) ? "" : "non-finite coordinates were accepted";
}

CaseResult fuzzConformalDisk(Rng& rng)
{
  TriangleSoup soup = diskSurface(rng);
  for (int k = static_cast<int>(pick(rng, 3)); k > 0; --k) // 0 to 2 mutations
  {
    mutateMesh(soup, rng);
  }
  if (const char* dump = std::getenv("OTPARAM_FUZZ_DUMP"))
  {
    std::ofstream(dump) << offText(soup);
  }
  ConformalStageOptions options;
  options.fillHoles = rng() % 4 != 0;
  if (rng() % 4 == 0)
  {
    options.centerPointId = static_cast<std::int64_t>(rng() % 400) - 50;
  }
  if (!options.check().empty())
  {
    return "";
  }
  const ConformalStage stage = runConformalStage(soup, options);
  if (!stage.status.error.empty() || stage.status.aborted)
  {
    return refused(stage.status);
  }
  Accepted = true;
  if (stage.map.uv.size() != stage.surface.mesh.points.size() || !finite(stage.map.uv))
  {
    return "a conformal disk map called good has non-finite or missing coordinates";
  }
  return stage.figures.flippedTriangles > 0 && !mentions(stage.status, "flip")
    ? "flipped triangles without a warning"
    : "";
}

CaseResult fuzzConformalSphere(Rng& rng)
{
  TriangleSoup soup = sphereSurface(rng);
  for (int k = static_cast<int>(pick(rng, 3)); k > 0; --k) // 0 to 2 mutations
  {
    mutateMesh(soup, rng);
  }
  if (const char* dump = std::getenv("OTPARAM_FUZZ_DUMP"))
  {
    std::ofstream(dump) << offText(soup);
  }
  // With FillHoles the mutations' holes are closed for the map, then the fill dropped.
  SphereConformalStage stage =
    runSphereConformalStage(soup, ConformalSphereMapOptions(), rng() % 2);
  if (!stage.status.error.empty() || stage.status.aborted)
  {
    return refused(stage.status);
  }
  Accepted = true;
  keepInputPart(stage);
  if (stage.map.sphere.size() != stage.surface.mesh.points.size() || !finite(stage.map.sphere) ||
    stage.surface.mesh.points.size() != stage.inputPoints)
  {
    return "a conformal sphere map called good has non-finite or missing coordinates";
  }
  return stage.figures.flippedTriangles > 0 && !mentions(stage.status, "flip")
    ? "flipped triangles without a warning"
    : "";
}

// A planar sampling stage's outcome: refused cleanly, or samples that are finite with a mass each.
CaseResult refusedOrSound(const SamplingStage& stage)
{
  if (!stage.status.error.empty() || stage.status.aborted)
  {
    return refused(stage.status);
  }
  Accepted = true;
  return finite(stage.result.samples) && finite(stage.result.mass) &&
      stage.result.mass.size() == stage.result.samples.size()
    ? ""
    : "samples called good are non-finite or without one mass each";
}

CaseResult fuzzPlanarSampler(Rng& rng)
{
  const otparam::testing::PlanarMesh disk =
    otparam::testing::makePlanarDisk(3 + static_cast<int>(pick(rng, 8)));
  std::vector<Vec2> points = disk.points;
  std::vector<Triangle> triangles = disk.triangles;
  const bool perPoint = rng() % 2;
  std::vector<double> values(perPoint ? points.size() : triangles.size());
  for (size_t i = 0; i < values.size(); ++i)
  {
    values[i] = 1.0 + 100.0 * static_cast<double>(rng() % 1000) / 1000.0;
  }
  SamplerOptions options;
  options.numberOfSamples = 50 + static_cast<long long>(pick(rng, 400));
  switch (rng() % 3)
  {
    case 0:
      mutateValues(values, rng);
      break;
    case 1:
      mutateSampler(options, rng);
      break;
    default:
      if (!points.empty())
      {
        (&points[pick(rng, points.size())].x)[pick(rng, 2)] = hostileNumber(rng);
      }
      break;
  }
  if (rng() % 5 == 0 && !triangles.empty())
  {
    triangles[pick(rng, triangles.size())][pick(rng, 3)] = static_cast<int>(points.size());
  }
  const size_t expected = perPoint ? points.size() : triangles.size();
  if (values.size() != expected ||
    !checkDensityValues(values, perPoint ? "point" : "cell").empty() ||
    !checkSamplerOptions(options).empty())
  {
    return "";
  }
  const SamplingStage stage = runSamplingStage(points, triangles,
    perPoint ? values : std::vector<double>(), perPoint ? std::vector<double>() : values, options);
  return refusedOrSound(stage);
}

// Planar domains whose triangles are each sound but whose whole is not: a patch laid across the
// others (no shared point), a point thrown across its neighbours, a patch shrunk towards the
// end of double precision, a sliver spike a few units in the last place wide. CGAL's mesher
// crashed on the first and third kinds (a crowded finger's stage domains; robustness.md,
// finding 7); the sampler must refuse them or sample them.
CaseResult fuzzPlanarSamplerOnBrokenDomains(Rng& rng)
{
  const otparam::testing::PlanarMesh disk =
    otparam::testing::makePlanarDisk(4 + static_cast<int>(pick(rng, 8)));
  std::vector<Vec2> points = disk.points;
  std::vector<Triangle> triangles = disk.triangles;
  const int centre = static_cast<int>(pick(rng, points.size()));
  // The triangles within `radius` of the centre point, as a patch.
  const double radius = 0.05 + 0.5 * static_cast<double>(rng() % 1000) / 1000.0;
  std::vector<size_t> patch;
  for (size_t t = 0; t < triangles.size(); ++t)
  {
    if (norm(points[triangles[t][0]] - points[centre]) < radius)
    {
      patch.push_back(t);
    }
  }
  switch (rng() % 4)
  {
    case 0: // the patch copied onto points of its own, moved across the others
    {
      const Vec2 shift = { 0.1 + 1.4 * static_cast<double>(rng() % 1000) / 1000.0,
        0.7 * static_cast<double>(rng() % 1000) / 1000.0 };
      std::map<int, int> copy;
      for (size_t t : patch)
      {
        Triangle moved = triangles[t];
        for (int& v : moved)
        {
          const auto [it, added] = copy.emplace(v, static_cast<int>(points.size()));
          if (added)
          {
            points.push_back(points[v] + shift);
          }
          v = it->second;
        }
        triangles.push_back(moved);
      }
      break;
    }
    case 1: // a point thrown across its neighbours
      points[centre] = points[centre] +
        Vec2{ 0.4 * static_cast<double>(rng() % 1000) / 1000.0 - 0.2,
          0.4 * static_cast<double>(rng() % 1000) / 1000.0 - 0.2 };
      break;
    case 2: // the patch shrunk by 1e-9 .. 1e-17 towards its centre
    {
      const double factor = std::pow(10.0, -9.0 - static_cast<double>(pick(rng, 9)));
      std::set<int> moved;
      for (size_t t : patch)
      {
        moved.insert(triangles[t].begin(), triangles[t].end());
      }
      const Vec2 c = points[centre];
      for (int v : moved)
      {
        points[v] = c + factor * (points[v] - c);
      }
      break;
    }
    default: // a spike 1-64 units in the last place wide on a boundary edge of the unit circle
    {
      const Vec2 a = { 1.0, 0.0 };
      const double ulp = std::nextafter(1.0, 2.0) - 1.0;
      const double width = static_cast<double>(1 + pick(rng, 64)) * ulp;
      const int base = static_cast<int>(points.size());
      points.push_back(a);
      points.push_back(a + Vec2{ 0.0, width });
      points.push_back(a + Vec2{ 1.0, 0.5 * width });
      triangles.push_back({ base, base + 2, base + 1 });
      break;
    }
  }
  SamplerOptions options;
  options.numberOfSamples = 50 + static_cast<long long>(pick(rng, 400));
  const SamplingStage stage =
    runSamplingStage(points, triangles, {}, std::vector<double>(triangles.size(), 1.0), options);
  return refusedOrSound(stage);
}

CaseResult fuzzSphericalSampler(Rng& rng)
{
  const SurfaceMesh sphere = otparam::testing::convexHullMesh(
    otparam::testing::fibonacciSphere(30 + static_cast<int>(pick(rng, 300))));
  std::vector<Vec3> points = sphere.points;
  std::vector<double> density(sphere.triangles.size());
  for (double& g : density)
  {
    g = 1.0 + 50.0 * static_cast<double>(rng() % 1000) / 1000.0;
  }
  SamplerOptions options;
  options.numberOfSamples = 50 + static_cast<long long>(pick(rng, 400));
  switch (rng() % 3)
  {
    case 0:
      mutateValues(density, rng);
      break;
    case 1:
      mutateSampler(options, rng);
      break;
    default:
      mutatePoints3(points, rng);
      break;
  }
  if (points.size() != sphere.points.size() || !pointsOnUnitSphere(points) ||
    density.size() != sphere.triangles.size() || !checkDensityValues(density, "cell").empty() ||
    !checkSamplerOptions(options).empty())
  {
    return "";
  }
  const SphereSamplingStage stage =
    runSphereSamplingStage(points, sphere.triangles, density, options);
  if (!stage.status.error.empty() || stage.status.aborted)
  {
    return refused(stage.status);
  }
  Accepted = true;
  return finite(stage.result.samples) && finite(stage.result.mass) ? ""
                                                                   : "non-finite samples or masses";
}

// The transport cases of either domain: the Diracs, the masses or the options broken, the
// adapters' checks, the solve, and the checks of a result called good.
template <class Point, class Solve>
CaseResult fuzzTransport(Rng& rng, std::vector<Point> diracs, int massDecades,
  void (*mutatePoints)(std::vector<Point>&, Rng&), const Solve& solve)
{
  std::vector<double> masses(diracs.size());
  for (double& m : masses)
  {
    m = std::pow(10.0, static_cast<double>(rng() % (100 * massDecades)) / 100.0);
  }
  OTOptions options;
  switch (rng() % 3)
  {
    case 0:
      mutatePoints(diracs, rng);
      if (masses.size() > diracs.size())
      {
        masses.resize(diracs.size());
      }
      break;
    case 1:
      mutateValues(masses, rng);
      break;
    default:
      mutateTransport(options, rng);
      break;
  }
  if (!checkTransportOptions(options, DefaultMaximumArcAngle).empty())
  {
    return "";
  }
  const auto stage = solve(diracs, masses, options);
  if (!stage.status.error.empty() || stage.status.aborted)
  {
    return refused(stage.status);
  }
  Accepted = true;
  const auto& r = stage.result;
  if (!finite(r.heights) || !finite(r.cellMass) || !finite(r.centroids))
  {
    return "a transport called good has non-finite heights, masses or centroids";
  }
  return r.converged && !(r.relativeError <= options.tolerance)
    ? "converged is claimed above the tolerance"
    : "";
}

CaseResult fuzzPlanarTransport(Rng& rng)
{
  const auto disk = makeUnitDiskSource();
  std::vector<Vec2> diracs =
    otparam::testing::randomInDisk(3 + pick(rng, 600), static_cast<unsigned>(rng() % 1000));
  return fuzzTransport(rng, std::move(diracs), 4, mutatePoints2,
    [&](const std::vector<Vec2>& y, const std::vector<double>& m, const OTOptions& o)
    { return runTransportStage(*disk, y, m, o, DefaultMaximumArcAngle); });
}

CaseResult fuzzSphericalTransport(Rng& rng)
{
  std::vector<Vec3> diracs =
    otparam::testing::fibonacciSphere(4 + static_cast<int>(pick(rng, 600)));
  return fuzzTransport(rng, std::move(diracs), 3, mutatePoints3,
    [](const std::vector<Vec3>& y, const std::vector<double>& m, const OTOptions& o)
    { return runSphereTransportStage(y, m, o, DefaultMaximumArcAngle); });
}

template <class Result>
CaseResult checkMap(const Result& run, const std::vector<Vec2>* uv, const std::vector<Vec3>* sphere)
{
  if (!run.status.error.empty() || run.status.aborted)
  {
    return refused(run.status);
  }
  Accepted = true;
  if ((uv && !finite(*uv)) || (sphere && !finite(*sphere)))
  {
    return "an area-preserving map called good has non-finite coordinates";
  }
  return run.figures.flippedTriangles > 0 && !mentions(run.status, "flip")
    ? "flipped triangles without a warning"
    : "";
}

CaseResult fuzzPipeline(Rng& rng, bool sphere)
{
  TriangleSoup soup = sphere ? sphereSurface(rng) : diskSurface(rng);
  AreaPreservingOptions options;
  options.sampling.numberOfSamples = 30 + static_cast<long long>(pick(rng, 300));
  switch (rng() % 3)
  {
    case 0:
      mutateMesh(soup, rng);
      break;
    case 1:
      mutateSampler(options.sampling, rng);
      break;
    default:
      mutateTransport(options.transport, rng);
      break;
  }
  if (!options.check().empty())
  {
    return "";
  }
  if (const char* dump = std::getenv("OTPARAM_FUZZ_DUMP"))
  {
    std::ofstream(dump) << offText(soup);
  }
  if (sphere)
  {
    const SphereParameterizationResult run = parameterizeSphere(soup, options);
    return checkMap(run, nullptr, &run.composition.sphere);
  }
  const AreaPreservingResult run = parameterizeDisk(soup, options);
  return checkMap(run, &run.composition.uv, nullptr);
}

struct Entry
{
  const char* name;
  std::function<CaseResult(Rng&)> run;
};

std::vector<Entry> entries()
{
  return {
    { "read-off", [](Rng& r) { return fuzzReader(r, false); } },
    { "read-obj", [](Rng& r) { return fuzzReader(r, true); } },
    { "conformal-disk", fuzzConformalDisk },
    { "conformal-sphere", fuzzConformalSphere },
    { "sampler-plane", fuzzPlanarSampler },
    { "sampler-plane-broken", fuzzPlanarSamplerOnBrokenDomains },
    { "sampler-sphere", fuzzSphericalSampler },
    { "transport-plane", fuzzPlanarTransport },
    { "transport-sphere", fuzzSphericalTransport },
    { "pipeline-disk", [](Rng& r) { return fuzzPipeline(r, false); } },
    { "pipeline-sphere", [](Rng& r) { return fuzzPipeline(r, true); } },
  };
}

struct Arguments
{
  long long cases = 100;
  unsigned long long seed = 1;
  std::string entry;
  long long only = -1;
  double caseSeconds = 60.0;
  bool list = false;
  bool verbose = false;
};

bool parse(int argc, char** argv, Arguments& a)
{
  for (int i = 1; i < argc; ++i)
  {
    const std::string key = argv[i];
    const bool hasValue = i + 1 < argc;
    if (key == "--list")
    {
      a.list = true;
    }
    else if (key == "--verbose")
    {
      a.verbose = true;
    }
    else if (key == "--cases" && hasValue)
    {
      a.cases = std::atoll(argv[++i]);
    }
    else if (key == "--seed" && hasValue)
    {
      a.seed = std::strtoull(argv[++i], nullptr, 10);
    }
    else if (key == "--entry" && hasValue)
    {
      a.entry = argv[++i];
    }
    else if (key == "--case" && hasValue)
    {
      a.only = std::atoll(argv[++i]);
    }
    else if (key == "--case-seconds" && hasValue)
    {
      a.caseSeconds = std::atof(argv[++i]);
    }
    else
    {
      return false;
    }
  }
  return a.cases > 0 && a.caseSeconds > 0.0;
}
} // namespace

int main(int argc, char** argv)
{
  // libgomp reads OMP_WAIT_POLICY as it loads, before main, so the fuzzer runs itself again
  // with it set, as the command line and the test runner do: spinning idle threads beside other
  // work made transport-plane cases of 0.06-0.09 s (seeds 14 and 15) run past the watchdog.
  if (!std::getenv("OMP_WAIT_POLICY"))
  {
    setenv("OMP_WAIT_POLICY", "passive", 1);
    execv("/proc/self/exe", argv); // returns only when it fails: then go on spinning
  }
  Arguments args;
  if (!parse(argc, argv, args))
  {
    std::fprintf(stderr,
      "usage: %s [--cases N] [--seed S] [--entry NAME] [--case K] [--case-seconds T] [--list] "
      "[--verbose]\n",
      argv[0]);
    return 2;
  }
  for (int signal : { SIGSEGV, SIGABRT, SIGFPE, SIGBUS, SIGILL })
  {
    std::signal(signal, reportCrash);
  }
  if (__sanitizer_set_death_callback)
  {
    __sanitizer_set_death_callback(reportSanitizerDeath);
  }
  if (args.list)
  {
    for (const Entry& e : entries())
    {
      std::printf("%s\n", e.name);
    }
    return 0;
  }
  Watchdog watchdog(args.caseSeconds);
  std::printf("| entry point | cases | refused or failed cleanly | accepted | findings | "
              "seconds | slowest case, s |\n|---|---|---|---|---|---|---|\n");
  int findings = 0;
  for (const Entry& entry : entries())
  {
    if (!args.entry.empty() && args.entry != entry.name)
    {
      continue;
    }
    long long accepted = 0, declined = 0, found = 0;
    double slowest = 0.0;
    const auto start = std::chrono::steady_clock::now();
    const long long first = args.only >= 0 ? args.only : 0;
    long long slowestCase = first;
    const long long last = args.only >= 0 ? args.only + 1 : args.cases;
    for (long long k = first; k < last; ++k)
    {
      std::snprintf(CurrentCase, sizeof CurrentCase, "--entry %s --seed %llu --case %lld",
        entry.name, args.seed, k);
      // One generator per case, so that any case is rerun alone.
      std::seed_seq seeds{ static_cast<unsigned>(args.seed), static_cast<unsigned>(k),
        static_cast<unsigned>(std::hash<std::string>()(entry.name)) };
      Rng rng(seeds);
      watchdog.startCase();
      Accepted = false;
      Refusal = "(checks in the driver)";
      const auto caseStart = std::chrono::steady_clock::now();
      const CaseResult result = entry.run(rng);
      const double caseSeconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - caseStart).count();
      if (caseSeconds > slowest)
      {
        slowest = caseSeconds;
        slowestCase = k;
      }
      if (!result.empty())
      {
        ++found;
        std::fprintf(stderr, "FINDING (%s): %s\n", CurrentCase, result.c_str());
      }
      ++(Accepted ? accepted : declined);
      if (args.verbose)
      {
        std::printf("%s: %.2f s, %s\n", CurrentCase, caseSeconds,
          Accepted ? "accepted" : ("refused: " + Refusal).c_str());
      }
    }
    const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("| %s | %lld | %lld | %lld | %lld | %.1f | %.2f (case %lld) |\n", entry.name,
      last - first, declined, accepted, found, seconds, slowest, slowestCase);
    std::fflush(stdout);
    findings += static_cast<int>(found);
  }
  std::snprintf(CurrentCase, sizeof CurrentCase, "none");
  std::printf("\n%d finding(s)\n", findings);
  return findings == 0 ? 0 : 1;
}
