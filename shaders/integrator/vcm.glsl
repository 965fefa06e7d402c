// Vertex merging (Georgiev, Krivanek, Davidovic and Slusallek 2012, "Light transport simulation
// with vertex connection and merging"; Hachisuka et al. 2012's unified path sampling): BDPT
// whose camera vertices also gather the light subpath vertices of every pixel's light subpath
// of the round that lie within the merge radius, as photon density estimation does, weighed
// against every connection strategy by MIS. Where light reaches the seen surfaces only through
// a gap (a door ajar, a lamp shade), a camera vertex's connection to its own light subpath is
// almost always occluded, while a round's light subpaths leave thousands of vertices beside it.
//
// A round is two dispatches (VCM_PHASE_* in shared/layout.h): the light phase traces each
// pixel's light subpath (as BDPT does, splatting its camera connections), stores its vertices
// and threads them onto the lists of a hash grid of cells 2r wide (one atomic exchange each);
// the camera phase traces each pixel's camera path, connects it to its own light subpath's
// stored vertices and merges at each non-delta vertex with those within r, in the 8 cells
// around it. Merging is biased by the radius; r shrinks as rounds pass (r_i = r_1 i^((a-1)/2),
// Knaus and Zwicker 2011), so the estimate converges.
//
// Included by integrator/bdpt.glsl after its MIS sums and LightVertex.
#ifndef PT_INTEGRATOR_VCM_GLSL
#define PT_INTEGRATOR_VCM_GLSL
#include "common/buffers.glsl"
#include "common/rng.glsl"
#include "shared/features.glsl"
#include "integrator/bdpt_vertex.glsl"

layout(buffer_reference, std430, buffer_reference_align = 4) coherent buffer VcmUintRef { uint v[]; };

// The dispatch's vertex merging parameters (GpuRenderPush), set by render.comp's main.
struct VcmDispatch {
    uint phase;
    float radius;
    uint cellMask;
    uint verticesPerPixel;
    uint64_t vertices;
    uint64_t cells;
    uint64_t pilot;
    uint pilotMask;
    float pilotCell;
    float keepTarget;
};
VcmDispatch vcm;

uint vcmPixelCount() { return scene.imageSize.x * scene.imageSize.y; }
uint vcmSlotCount() { return vcmPixelCount() * vcm.verticesPerPixel; }

Vec4Ref vcmRecord(uint slot) { return Vec4Ref(vcm.vertices + uint64_t(slot) * uint64_t(VCM_VERTEX_VEC4S * 16u)); }
VcmUintRef vcmCounts() {
    return VcmUintRef(vcm.vertices + uint64_t(vcmSlotCount()) * uint64_t(VCM_VERTEX_VEC4S * 16u));
}
VcmUintRef vcmCellHeads() { return VcmUintRef(vcm.cells); }
// The word of a stored vertex that links it to the next of its cell (the first vec4's w).
VcmUintRef vcmLinkOf(uint slot) {
    return VcmUintRef(vcm.vertices + uint64_t(slot) * uint64_t(VCM_VERTEX_VEC4S * 16u) + 12ul);
}

// Threads `slot` onto the list of `cell`, which is kept in decreasing slot order whatever order
// the invocations insert in (a lock-free sorted insertion: find the place, link the new vertex
// to its successor, swap it in if the predecessor still points there, else look again from the
// predecessor). So each cell's list, and the order a merge adds its vertices in, is the same
// however the work was scheduled: the image stays bit-identical.
void insertIntoCell(uint cell, uint slot) {
    uint prev = VCM_NO_VERTEX; // VCM_NO_VERTEX: the cell's head
    while (true) {
        uint cur = prev == VCM_NO_VERTEX ? atomicOr(vcmCellHeads().v[cell], 0u) : atomicOr(vcmLinkOf(prev).v[0], 0u);
        if (cur != VCM_NO_VERTEX && cur > slot) {
            prev = cur;
            continue;
        }
        atomicExchange(vcmLinkOf(slot).v[0], cur);
        memoryBarrierBuffer();
        uint seen = prev == VCM_NO_VERTEX ? atomicCompSwap(vcmCellHeads().v[cell], cur, slot)
                                          : atomicCompSwap(vcmLinkOf(prev).v[0], cur, slot);
        if (seen == cur) return;
    }
}

// The grid cell of a point: cells are twice the radius wide, so a sphere of the radius around a
// point lies within the 2x2x2 cells nearest it.
ivec3 vcmCellOf(vec3 p, float cellSize) {
    vec3 c = clamp(floor(p / cellSize), vec3(-1e9), vec3(1e9));
    return ivec3(c);
}

// A well-mixed hash: with Teschner et al.'s three products xor'ed, the low bits a power-of-two
// mask keeps collided often enough that the pilot gave one floor cell in eight of the two-rooms
// scene a crowded cell's count, and so a low keep probability: squares of noise there. `key`
// tells apart cells of one cube (the pilot's sides).
uint vcmHash(ivec3 c, uint key, uint mask) { return pcg4d(uvec4(uvec3(c), key)).x & mask; }
uint vcmCellHash(ivec3 c) { return vcmHash(c, 0x2545F491u, vcm.cellMask); }

// Where a round's light subpaths leave many vertices (beside the light), a merge would gather
// hundreds, and the 8 lanes of a SIMD group wait for the busiest. So a vertex joins the grid with
// probability min(1, keepTarget / n), n the vertices a pilot round left in its pilot cell, and its
// merges count it 1 / that. MIS weighs a merge at x by the same probability (its density there).
// A pilot cell is a cube and a side: of the six axis directions, the one nearest nLit, the
// geometric normal on the side the light arrives from. Cubes alone mixed the two faces of a thin
// door, one lit by the lamp, the other seen by the camera through the gap: the seen face took the
// lit face's count, its few kept vertices weighed tens of times each (grain all over the door).
// A function of the point and side alone, the same for both subpaths and every round.
uint pilotSide(vec3 nLit) {
    vec3 a = abs(nLit);
    uint axis = a.x >= a.y && a.x >= a.z ? 0u : (a.y >= a.z ? 1u : 2u);
    return axis * 2u + (nLit[axis] < 0.0 ? 1u : 0u);
}

uint pilotCellOf(vec3 p, vec3 nLit) { return vcmHash(vcmCellOf(p, vcm.pilotCell), pilotSide(nLit), vcm.pilotMask); }

float mergeKeep(vec3 p, vec3 nLit) {
    if (!MERGING) return 1.0;
    float n = float(VcmUintRef(vcm.pilot).v[pilotCellOf(p, nLit)]);
    return n > vcm.keepTarget ? vcm.keepTarget / n : 1.0;
}

// ---- The light phase: a pixel's light subpath stored, its vertices in the grid ----

// Stores vertex `index` of pixel `pixelIndex`'s light subpath and threads it onto its cell's list.
// ngLit is the geometric normal on the side the light arrived from, for merges' side test.
void storeVcmVertex(uint pixelIndex, uint index, LightVertex v, vec3 ngLit, float uKeep) {
    if (vcm.phase == VCM_PHASE_PILOT) {
        atomicAdd(VcmUintRef(vcm.pilot).v[pilotCellOf(v.p, ngLit)], 1u);
        return;
    }
    uint slot = pixelIndex * vcm.verticesPerPixel + index;
    Vec4Ref r = vcmRecord(slot);
    r.v[1] = vec4(v.ray.origin, v.hit.t);
    r.v[2] = vec4(v.ray.direction, uintBitsToFloat(v.hit.primitive));
    r.v[3] = vec4(v.hit.bary, uintBitsToFloat(v.hit.instance), uintBitsToFloat(v.segments));
    r.v[4] = vec4(v.beta, v.mis.cVCM);
    r.v[5] = vec4(v.mis.cVC, v.mis.eVCM, v.mis.eVC, v.mis.mVC);
    float keep = mergeKeep(v.p, ngLit);
    r.v[6] = vec4(ngLit, 1.0 / keep);
    // Every vertex stays for its own camera path's connections; the grid keeps a share. The
    // first vec4 holds what a merge's search reads of every vertex it passes: the point and the
    // next vertex of the cell.
    r.v[0] = vec4(v.p, uintBitsToFloat(VCM_NO_VERTEX));
    if (uKeep < keep) insertIntoCell(vcmCellHash(vcmCellOf(v.p, 2.0 * vcm.radius)), slot);
}

void storeVcmVertexCount(uint pixelIndex, uint count) { vcmCounts().v[pixelIndex] = count; }

// ---- The camera phase ----

LightVertex loadVcmVertex(uint slot) {
    Vec4Ref r = vcmRecord(slot);
    vec4 v0 = r.v[0], v1 = r.v[1], v2 = r.v[2], v3 = r.v[3], v4 = r.v[4], v5 = r.v[5];
    LightVertex v;
    v.p = v0.xyz;
    v.segments = floatBitsToUint(v3.w);
    v.ray.origin = v1.xyz;
    v.hit.t = v1.w;
    v.ray.direction = v2.xyz;
    v.hit.primitive = floatBitsToUint(v2.w);
    v.hit.bary = v3.xy;
    v.hit.instance = floatBitsToUint(v3.z);
    v.beta = v4.xyz;
    v.mis = MisSums(v4.w, v5.x, v5.y, v5.z, v5.w);
    return v;
}

uint vcmVertexCount(uint pixelIndex) { return vcmCounts().v[pixelIndex]; }

// The square of the largest distance from the seen surface's tangent plane a merged vertex may
// have, in radii: a quarter of the radius, well above a curved surface's sag within it unless
// the curvature radius is under twice the merge radius.
const float kMergeSlab = 0.0625;

// What merging at camera vertex si (shading in `frame`, reached from wo after `depth` segments,
// MIS sums `mis`) gathers: every stored light vertex within the radius on the same surface, the
// camera vertex's BSDF applied to the direction its light arrived from, weighted against every
// other strategy, over pi r^2 and the round's light subpaths. Times the camera path's throughput.
vec3 mergeAtVertex(SurfaceInteraction si, GpuMaterial mat, Frame frame, vec3 wo, uint depth, MisSums mis) {
    float r = vcm.radius, r2 = r * r, cellSize = 2.0 * r;
    vec3 q = si.p / cellSize;
    ivec3 low = vcmCellOf(si.p, cellSize) - ivec3(lessThan(fract(q), vec3(0.5)));
    bool transmissive = isTransmissiveSurface(mat);
    vec3 ngSeen = dot(wo, si.ng) >= 0.0 ? si.ng : -si.ng;
    vec3 sum = vec3(0.0);
    uint visited[8];
    for (uint k = 0u; k < 8u; ++k) {
        uint cell = vcmCellHash(low + ivec3(k & 1u, (k >> 1u) & 1u, k >> 2u));
        // Two cells that hash to the same list would count its vertices twice.
        bool seen = false;
        for (uint j = 0u; j < k; ++j) seen = seen || visited[j] == cell;
        visited[k] = cell;
        if (seen) continue;
        uint slot = vcmCellHeads().v[cell];
        while (slot != VCM_NO_VERTEX) {
            Vec4Ref rec = vcmRecord(slot);
            vec4 v0 = rec.v[0];
            vec3 d = v0.xyz - si.p;
            // Within the radius, and near the seen surface's tangent plane: a point on another
            // surface parallel to it behind a thin gap (the far side of a door's slit) is no
            // sample of the light here, and merging it leaks that side's light through the gap.
            float offPlane = dot(d, si.ng);
            if (dot(d, d) <= r2 && offPlane * offPlane <= kMergeSlab * r2 &&
                depth + floatBitsToUint(rec.v[3].w) <= scene.maxDepth) {
                vec4 v6 = rec.v[6];
                vec3 ngLit = v6.xyz;
                // The same surface, lit from the side seen (either side through a transmissive one).
                float facing = dot(ngLit, ngSeen);
                if (transmissive ? abs(facing) > 0.5 : facing > 0.5) {
                    vec3 wLight = -rec.v[2].xyz;
                    VertexEval e;
                    float cosLightIn = abs(dot(wLight, si.ng));
                    if (cosLightIn > 1e-7 && evalInFrame(si, mat, frame, wo, wLight, e)) {
                        vec4 v4 = rec.v[4], v5 = rec.v[5];
                        MisSums lm = MisSums(v4.w, v5.x, v5.y, v5.z, v5.w);
                        float towardsLight = misPower(e.pdfTowardsLight), towardsCamera = misPower(e.pdfTowardsCamera);
                        vec3 lightSide = vec3(
                            lm.cVCM + lm.cVC * towardsLight, lm.eVCM + lm.eVC * towardsLight, lm.mVC * towardsLight);
                        vec3 cameraSide = vec3(mis.cVCM + mis.cVC * towardsCamera, mis.eVCM + mis.eVC * towardsCamera,
                            mis.mVC * towardsCamera);
                        // The merge's density is scaled by the keep probability of the light
                        // vertex it takes (v6.w is its inverse), not of the camera vertex's cell:
                        // the two can sit in pilot cells of very different counts, and a weight
                        // from the camera's side left 1 / keep unchecked (fireflies of 40x).
                        float others = otherStrategies(lightSide + cameraSide, STRATEGY_MERGE) * misPower(v6.w);
                        float weight = BDPT_STRATEGY == BDPT_ALL_STRATEGIES ? 1.0 / (1.0 + others) : 0.0;
                        sum += v4.xyz * e.fCos * (weight * v6.w / cosLightIn);
                    }
                }
            }
            slot = floatBitsToUint(v0.w); // (written in the light phase, before this dispatch)
        }
    }
    return sum / (PI * r2 * float(vcmPixelCount()));
}

#endif
