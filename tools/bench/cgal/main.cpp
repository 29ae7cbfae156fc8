// CGAL's edge-collapse simplification, for tools/bench/peers (a peer, not part of decimate):
//   cgal-simplify lt|gh IN.ply OUT.ply TRIANGLES
// lt: Lindström–Turk cost and placement (CGAL's default policies); gh: Garland–Heckbert
// plane quadrics. The input is read as a polygon soup, repaired and oriented the way CGAL's
// documentation recommends for scans (non-manifold vertices are duplicated), so every mesh
// of the bench can be read. Prints the seconds the simplification call alone took.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/LindstromTurk.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace SMS = CGAL::Surface_mesh_simplification;
namespace PMP = CGAL::Polygon_mesh_processing;

// Stops when the mesh has no more than the target's triangles (CGAL 5.5 counts edges only).
struct FaceCountStop {
    std::size_t target;
    template <typename F, typename Profile>
    bool operator()(const F&, const Profile& profile, std::size_t, std::size_t) const {
        return profile.surface_mesh().number_of_faces() <= target;
    }
};

static bool read_mesh(const char* path, Mesh& mesh) {
    std::vector<Point> points;
    std::vector<std::vector<std::size_t>> polygons;
    if (!CGAL::IO::read_polygon_soup(path, points, polygons)) return false;
    PMP::repair_polygon_soup(points, polygons);
    PMP::orient_polygon_soup(points, polygons);
    PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
    return CGAL::is_triangle_mesh(mesh);
}

int main(int argc, char** argv) {
    if (argc != 5) {
        std::fprintf(stderr, "usage: cgal-simplify lt|gh IN.ply OUT.ply TRIANGLES\n");
        return 2;
    }
    const std::string policy = argv[1];
    Mesh mesh;
    if (!read_mesh(argv[2], mesh)) {
        std::fprintf(stderr, "cgal-simplify: cannot read %s as a triangle mesh\n", argv[2]);
        return 1;
    }
    const FaceCountStop stop{static_cast<std::size_t>(std::strtoull(argv[4], nullptr, 10))};
    const auto start = std::chrono::steady_clock::now();
    if (policy == "lt") {
        SMS::edge_collapse(mesh, stop);
    } else if (policy == "gh") {
        SMS::GarlandHeckbert_plane_policies<Mesh, Kernel> gh(mesh);
        SMS::edge_collapse(mesh, stop,
                           CGAL::parameters::get_cost(gh.get_cost()).get_placement(gh.get_placement()));
    } else {
        std::fprintf(stderr, "cgal-simplify: unknown policy '%s' (lt or gh)\n", policy.c_str());
        return 2;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    mesh.collect_garbage();
    if (!CGAL::IO::write_polygon_mesh(argv[3], mesh, CGAL::parameters::stream_precision(17))) {
        std::fprintf(stderr, "cgal-simplify: cannot write %s\n", argv[3]);
        return 1;
    }
    std::printf("%.3f\n", seconds);
    return 0;
}
