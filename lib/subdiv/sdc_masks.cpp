#include "subdiv/sdc_masks.h"

namespace limn {

OpenSubdiv::Sdc::Options toSdcOptions(const SchemeOptions& o) {
    using Opt = OpenSubdiv::Sdc::Options;
    Opt s;
    switch (o.boundary) {
    case BoundaryRule::None: s.SetVtxBoundaryInterpolation(Opt::VTX_BOUNDARY_NONE); break;
    case BoundaryRule::EdgeOnly: s.SetVtxBoundaryInterpolation(Opt::VTX_BOUNDARY_EDGE_ONLY); break;
    case BoundaryRule::EdgeAndCorner:
        s.SetVtxBoundaryInterpolation(Opt::VTX_BOUNDARY_EDGE_AND_CORNER);
        break;
    }
    s.SetCreasingMethod(o.creaseMethod == CreaseMethod::Chaikin ? Opt::CREASE_CHAIKIN
                                                                : Opt::CREASE_UNIFORM);
    s.SetTriangleSubdivision(o.triangles == TriangleSubdivision::Smooth ? Opt::TRI_SUB_SMOOTH
                                                                        : Opt::TRI_SUB_CATMARK);
    s.SetFVarLinearInterpolation(static_cast<Opt::FVarLinearInterpolation>(o.fvar));
    return s;
}

void gatherNeighborhood(const Topology& topo, uint32_t v, VertexNeighborhood& out) {
    out.vertex = v;
    out.edges.clear();
    out.ringVertex.clear();
    out.faces.clear();
    out.diagonal.clear();
    uint32_t start = topo.vertexFirstOutgoing(v);
    out.boundary = topo.twin(start) == kNone;
    uint32_t h = start, last = start;
    do {
        out.edges.push_back(topo.edge(h));
        out.ringVertex.push_back(topo.destination(h));
        out.faces.push_back(topo.face(h));
        out.diagonal.push_back(topo.faceSize(topo.face(h)) == 4 ? topo.vertex(topo.next(topo.next(h)))
                                                                : kNone);
        last = h;
        h = topo.rotateCCW(h);
    } while (h != kNone && h != start);
    if (out.boundary) { // the trailing boundary edge arrives at v
        uint32_t p = topo.prev(last);
        out.edges.push_back(topo.edge(p));
        out.ringVertex.push_back(topo.vertex(p));
    }
}

} // namespace limn
