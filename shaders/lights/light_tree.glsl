// Which light to sample from a shading point: by the light tree where the scene has one
// (src/lights/light_tree.h; Conty Estevez and Kulla 2018, pbrt-v4's BVHLightSampler), else by
// the power CDF. The tree is descended by each child's importance at the point: its power over
// the squared distance, times how far its lights' normals and the point's own normal turn
// towards each other, bounded over the node's box. The pmf of a given light (for MIS, when a
// BSDF ray hits it) follows the light's stored trail from the root with the same arithmetic.
#ifndef PT_LIGHTS_LIGHT_TREE_GLSL
#define PT_LIGHTS_LIGHT_TREE_GLSL
#include "common/buffers.glsl"
#include "lights/light_common.glsl"
#include "shared/features.glsl"

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer LightTreeRef { GpuLightTreeNode v[]; };

const float LIGHT_TREE_ONE_MINUS_EPSILON = 0.99999994;
const uint LIGHT_TREE_MAX_DEPTH = 64u; // trails are 64-bit
// A floor on the squared distance (in scene radii) for a point light the point sits on.
const float LIGHT_TREE_MIN_DISTANCE2 = 1e-30;

struct LightChoice {
    uint index; // NO_LIGHT: none can light the point
    float pmf;
};

bool lightTreeActive() { return LIGHT_TREE && scene.lightTreeNodes != 0ul; }

// cos(a - b) and sin(a - b) for angles a, b in [0, pi], clamped to 0 where a < b.
float cosSubClamped(float sinA, float cosA, float sinB, float cosB) {
    return cosA > cosB ? 1.0 : cosA * cosB + sinA * sinB;
}
float sinSubClamped(float sinA, float cosA, float sinB, float cosB) {
    return cosA > cosB ? 0.0 : sinA * cosB - cosA * sinB;
}

// An upper bound, up to a common factor, of what the node's lights can send to point p with
// normal n (n = 0: no normal term). Zero only where none of them can light p.
float lightNodeImportance(GpuLightTreeNode node, vec3 p, vec3 n) {
    // Lengths in units of the scene's radius (a common factor of every node's importance).
    float invScale = scene.lightTreeInvScale;
    vec3 centre = 0.5 * (node.boundsMin + node.boundsMax);
    vec3 halfDiagonal = (0.5 * invScale) * (node.boundsMax - node.boundsMin);
    float r2 = dot(halfDiagonal, halfDiagonal);
    vec3 d = (p - centre) * invScale; // from the lights to the point
    float dist2 = dot(d, d);
    vec3 wi = dist2 > 0.0 ? d * inversesqrt(dist2) : vec3(0.0, 0.0, 1.0);
    // The cone of directions from p that holds the box's bounding sphere (all of them inside it).
    float cosB = -1.0;
    if (dist2 > r2) cosB = sqrt(max(0.0, 1.0 - r2 / dist2));
    float sinB = sqrt(max(0.0, 1.0 - cosB * cosB));
    // The angle between the normals' cone and the direction to p, less the cone and the box.
    float cosW = dot(node.axis, wi);
    if ((node.flags & LIGHT_NODE_TWO_SIDED) != 0u) cosW = abs(cosW);
    float sinW = sqrt(max(0.0, 1.0 - cosW * cosW));
    float cosX = cosSubClamped(sinW, cosW, node.sinThetaO, node.cosThetaO);
    float sinX = sinSubClamped(sinW, cosW, node.sinThetaO, node.cosThetaO);
    float cosP = cosSubClamped(sinX, cosX, sinB, cosB);
    if (cosP <= node.cosThetaE) return 0.0;
    // The distance is at least the bounding sphere's radius: a point among the lights is not
    // infinitely close to all of them.
    float importance = node.phi * cosP / max(max(dist2, r2), LIGHT_TREE_MIN_DISTANCE2);
    if (n != vec3(0.0)) {
        float cosI = abs(dot(wi, n));
        float sinI = sqrt(max(0.0, 1.0 - cosI * cosI));
        importance *= cosSubClamped(sinI, cosI, sinB, cosB);
    }
    return max(importance, 0.0);
}

// The probability of choosing the first of two children at p, or -1 where neither can light p.
float firstChildProbability(GpuLightTreeNode first, GpuLightTreeNode second, vec3 p, vec3 n) {
    float i0 = lightNodeImportance(first, p, n);
    float i1 = lightNodeImportance(second, p, n);
    float sum = i0 + i1;
    return sum > 0.0 ? i0 / sum : -1.0;
}

// Whether light selection with random number u descends the tree: otherwise it takes the power
// CDF (with a tree, its tail above the tree's share: the lights at infinity).
bool choosesInTree(float u) { return lightTreeActive() && u < scene.lightTreeShare; }

// The light the tree chooses at x with normal n (choosesInTree(u)), with its pmf.
LightChoice chooseTreeLight(vec3 x, vec3 n, float u) {
    LightChoice c;
    c.index = NO_LIGHT;
    c.pmf = 0.0;
    float share = scene.lightTreeShare;
    LightTreeRef nodes = LightTreeRef(scene.lightTreeNodes);
    u = min(u / share, LIGHT_TREE_ONE_MINUS_EPSILON);
    float pmf = share;
    uint i = 0u;
    GpuLightTreeNode node = nodes.v[0];
    for (uint step = 0u; step <= LIGHT_TREE_MAX_DEPTH; ++step) {
        if ((node.flags & LIGHT_NODE_LEAF) != 0u) {
            c.index = node.child;
            c.pmf = pmf;
            return c;
        }
        GpuLightTreeNode first = nodes.v[i + 1u];
        GpuLightTreeNode second = nodes.v[node.child];
        float p0 = firstChildProbability(first, second, x, n);
        if (p0 < 0.0) return c;
        if (u < p0) {
            i = i + 1u;
            node = first;
            u = min(u / p0, LIGHT_TREE_ONE_MINUS_EPSILON);
            pmf *= p0;
        } else {
            i = node.child;
            node = second;
            u = min((u - p0) / (1.0 - p0), LIGHT_TREE_ONE_MINUS_EPSILON);
            pmf *= 1.0 - p0;
        }
    }
    return c;
}

// The light light sampling chooses at x with normal n, by the tree or the power CDF.
LightChoice chooseLight(vec3 x, vec3 n, float u) {
    if (choosesInTree(u)) return chooseTreeLight(x, n, u);
    LightChoice c;
    c.index = selectLight(u);
    c.pmf = sceneLights.v[c.index].pmf;
    return c;
}

// The probability that chooseLight(x, n, .) picks light `index` (`light`, its table entry).
float lightSelectionPmf(uint index, GpuLight light, vec3 x, vec3 n) {
    if (!lightTreeActive() || isInfiniteLight(light)) return light.pmf;
    LightTreeRef nodes = LightTreeRef(scene.lightTreeNodes);
    uint64_t trail = Uint64Ref(scene.lightTreeTrails).v[index];
    float pmf = scene.lightTreeShare;
    uint i = 0u;
    GpuLightTreeNode node = nodes.v[0];
    for (uint step = 0u; step <= LIGHT_TREE_MAX_DEPTH; ++step) {
        if ((node.flags & LIGHT_NODE_LEAF) != 0u) return node.child == index ? pmf : 0.0;
        GpuLightTreeNode first = nodes.v[i + 1u];
        GpuLightTreeNode second = nodes.v[node.child];
        float p0 = firstChildProbability(first, second, x, n);
        if (p0 < 0.0) return 0.0;
        if ((trail & 1ul) != 0ul) {
            i = node.child;
            node = second;
            pmf *= 1.0 - p0;
        } else {
            i = i + 1u;
            node = first;
            pmf *= p0;
        }
        trail >>= 1u;
    }
    return 0.0;
}

#endif
