/* The second stage of the torus search, compiled (polyloops/generate/torus/stages.py describes the
 * search and is the reference; docs/searches.md, "Genus 1: the torus search", proves it).
 *
 * A state is a cellular arrangement on the torus, darts four a crossing counter-clockwise
 * (rot(d) = 4 (d / 4) + (d + 1) % 4), with a layer bit per dart: 1 on the third axis's loops,
 * 0 on the loops of the two-axis arrangement B.  A child adds one third-axis loop that crosses
 * only edges of B and each region of B (faces joined across third-axis edges) at most once.
 * Every face of the state is a disc that the new loop enters and leaves at most once, so the
 * new loop is a simple cycle of faces, consecutive faces across an edge of B and no two in
 * one region of B, and the child is built from the edges the cycle crosses.  Each cycle is
 * drawn once: from the least edge it crosses, in the direction whose second edge is less than
 * its last.
 *
 * children(twin, layer, limit) gives every child that
 *   - has at most `limit` crossings plus half the needs of its faces (torus.layered_need),
 *   - lets its loops be oriented as far as its third-axis loops decide (torus.orientable),
 *   - has a new loop whose crossings run in four runs at least, alternately with the two
 *     classes of B (torus.axis_runs), and leaves every loop of B room for two crossings with
 *     the third axis within the limit,
 *   - has the new loop as its canonical loop to delete: among the third axis's loops with
 *     fewest crossings, the one met first in the canonical numbering (McKay's test),
 * each as (canonical twin array as uint16, layer bytes, flags), flags bit 0 when it is a target
 * (a candidate map), bit 1 when the third axis crosses each class of B at least as often as
 * B crosses itself (B has the fewest crossings of the three two-axis arrangements) and bit 2
 * when no loop of B lacks third-axis crossings (torus._deficit is 0), possibly more than once
 * (isomorphic cycles give the same child: the caller keeps one), with the counts of what it
 * did.  While drawing, a path is abandoned when the faces it has cut already need more
 * crossings than the limit leaves, when B could no longer have the fewest crossings of the
 * three two-axis arrangements, or when the new loop already has more crossings than an old
 * third-axis loop (it would not be the canonical one to delete).
 *
 * Not reentrant: one static context, used with the GIL held, one call at a time per process.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdint.h>
#include <string.h>

#define MAXD 1024          /* darts of a child: four a crossing */
#define MAXL 128           /* loops */
#define THIRD 2            /* the class of the third axis's loops */
#define HUGE_NEED (1 << 20)

static inline int rot4(int d) { return (d & ~3) | ((d + 1) & 3); }
static inline int irot4(int d) { return (d & ~3) | ((d + 3) & 3); }
static inline int edge_of(const int *twin, int d) { return d < twin[d] ? d : twin[d]; }

/* torus.layered_need: twice a lower bound on the later crossings a face takes, from its sides,
 * the number of its sides of each class and whether it must still be cut (bad). */
static int layered_need(int sides, const int *count, int bad)
{
    if (count[THIRD] > 2) return HUGE_NEED;
    int n = 0;
    if (sides - 6 > n) n = sides - 6;
    if (6 - 2 * sides > n) n = 6 - 2 * sides;
    if (bad && 2 > n) n = 2;
    int k = (count[0] > 2 ? count[0] - 2 : 0) + (count[1] > 2 ? count[1] - 2 : 0);
    return k > n ? k : n;
}

/* A map with its faces (darts in face order, face by face), loops and their classes. */
typedef struct {
    int D;                    /* darts: four a crossing */
    int nf;                   /* faces */
    int nl;                   /* loops */
    int twin[MAXD];           /* the dart across the edge */
    unsigned char layer[MAXD];  /* 1 on a dart of the third axis's loops, 0 on B's */
    int face[MAXD];           /* the face on a dart's left */
    int fdart[MAXD];          /* the faces' darts, face by face, in order along each */
    int fstart[MAXD + 1];     /* face f: fdart[fstart[f] .. fstart[f + 1]) */
    int fpos[MAXD];           /* a dart's index in fdart */
    int loop[MAXD];           /* the loop a dart lies on */
    int lcross[MAXL];         /* crossings of each loop */
    int klass[MAXL];          /* 0 or 1 on B's loops (its bipartition), THIRD on the others */
} Map;

static void map_faces(Map *m)
{
    int k = 0;
    m->nf = 0;
    for (int d = 0; d < m->D; d++) m->face[d] = -1;
    for (int d = 0; d < m->D; d++) {
        if (m->face[d] >= 0) continue;
        m->fstart[m->nf] = k;
        int e = d;
        do { m->face[e] = m->nf; m->fpos[e] = k; m->fdart[k++] = e; e = irot4(m->twin[e]); } while (e != d);
        m->nf++;
    }
    m->fstart[m->nf] = k;
}

/* Loops (straight on through each crossing) and their crossings; -1 when a loop crosses itself
 * or there are too many. */
static int map_loops(Map *m)
{
    for (int d = 0; d < m->D; d++) m->loop[d] = -1;
    m->nl = 0;
    for (int d = 0; d < m->D; d++) {
        if (m->loop[d] >= 0) continue;
        if (m->nl >= MAXL) return -1;
        int e = d;
        do { m->loop[e] = m->loop[m->twin[e]] = m->nl; e = rot4(rot4(m->twin[e])); } while (e != d);
        m->lcross[m->nl++] = 0;
    }
    for (int d = 0; d < m->D; d++) {
        if (m->loop[d] == m->loop[rot4(d)]) return -1;
        m->lcross[m->loop[d]]++;
    }
    for (int l = 0; l < m->nl; l++) m->lcross[l] /= 2;
    return 0;
}

/* Twice the need of face f (layered_need with torus._bad: two sides on one loop, or a side
 * whose other side is in the face too); *simple_pair is not touched. */
static int face_need2(const Map *m, int f)
{
    static unsigned stamp[MAXL], now;
    int count[3] = {0, 0, 0}, bad = 0, a = m->fstart[f], b = m->fstart[f + 1];
    now++;
    for (int i = a; i < b; i++) {
        int d = m->fdart[i], l = m->loop[d];
        count[m->klass[l]]++;
        if (stamp[l] == now) bad = 1;
        stamp[l] = now;
        if (m->face[m->twin[d]] == f) bad = 1;
    }
    return layered_need(b - a, count, bad);
}

/* Per loop of B, the third-axis crossings it still lacks: its crossings, third axis against the
 * rest, must end in four runs at least (torus.axis_runs), and a later crossing adds at most
 * two runs; ceil((4 - runs) / 2), into lack[]; returns their sum. */
static int lacking(const Map *h, int *lack)
{
    static int changes[MAXL], seen[MAXL];
    for (int l = 0; l < h->nl; l++) { seen[l] = 0; changes[l] = 0; lack[l] = 0; }
    int total = 0;
    for (int d = 0; d < h->D; d++) {
        int l = h->loop[d];
        if (seen[l] || h->klass[l] == THIRD) continue;
        seen[l] = 1;
        int e = d, prev = -1, k0 = -1;
        do {
            int k = h->klass[h->loop[rot4(e)]] == THIRD;
            if (prev >= 0 && k != prev) changes[l]++;
            if (k0 < 0) k0 = k;
            prev = k;
            e = rot4(rot4(h->twin[e]));
        } while (e != d);
        if (prev != k0) changes[l]++;
        int runs = changes[l] ? changes[l] : 1;
        lack[l] = runs < 4 ? (5 - runs) / 2 : 0;
        total += lack[l];
    }
    return total;
}

/* The search context: the parent, and the cycle being drawn. */
typedef struct {
    Map p;                    /* the parent state */
    int region[MAXD];         /* per face of the parent: its region of B */
    int need2[MAXD];          /* per face of the parent: twice its need */
    int total2;               /* their sum */
    int limit;                /* the most crossings a target may have */
    int base;                 /* B's crossings */
    int pc;                   /* the parent's crossings */
    int budget;               /* limit - pc: the most crossings the new loop may make */
    int third_with[2];        /* crossings of the third axis with each class of B */
    int with_class[2];        /* and those of the cycle being drawn */
    int fewest_third;         /* fewest crossings of an old third-axis loop */
    int lack[MAXL];           /* per loop of B: the third-axis crossings it still lacks */
    int met[MAXL];            /* per loop of B: the cycle's crossings with it */
    int deficit;              /* their sum, less the cycle's crossings that serve them */
    int path[MAXD];           /* the darts the cycle crosses (each in the face it leaves) */
    unsigned char visited[MAXD];  /* per region of B */
    int end_face;             /* the face the cycle started from, where it closes */
    int end_region;           /* its region of B, entered last */
    int first_edge;           /* the least edge the cycle crosses (its start; each cycle drawn once) */
    PyObject *out;            /* the children found: a list of (twin, layer, flags) */
    int failed;               /* a Python error is set (out of memory): stop */
    long long nodes;          /* steps of the cycle drawn */
    long long closed;         /* cycles closed */
    long long bounded;        /* branches or children over the limit */
    long long inconsistent;   /* children whose loops no orientation fits */
    long long rejected;       /* children whose new loop is not the canonical one to delete */
    long long straight;       /* new loops crossing B in fewer than four runs */
} Ctx;

static Ctx ctx;
static Map child;
static int num[MAXD], order[MAXD], best[MAXD + 16], code[MAXD + 16];  /* the codes: the marks after the darts */

/* The child's code from root r in orientation o (rot, or irot when o is 1): per dart in the
 * breadth-first numbering, twice its twin's number plus its layer.  Returns -1 when it exceeds
 * best, 0 when equal, 1 when smaller (then it is in code); *first is the first loop of the
 * numbering in the set cand. */
static int code_from(const Map *h, int o, int r, int have_best, const unsigned char *cand, int *first)
{
    int cnt = 0, smaller = !have_best;
    for (int d = 0; d < h->D; d++) num[d] = -1;
    *first = -1;
#define VISIT(t0) do { int t_ = (t0); for (int j_ = 0; j_ < 4; j_++) { num[t_] = cnt; order[cnt++] = t_; \
        t_ = o ? irot4(t_) : rot4(t_); } } while (0)
    VISIT(r);
    for (int i = 0; i < h->D; i++) {
        int d = order[i], t = h->twin[d];
        if (*first < 0 && cand[h->loop[d]]) *first = h->loop[d];
        if (num[t] < 0) VISIT(t);
        int v = 2 * num[t] + h->layer[d];
        code[i] = v;
        if (!smaller) {
            if (v > best[i]) return -1;
            if (v < best[i]) smaller = 1;
        }
    }
#undef VISIT
    return smaller;
}

static int root_key(const Map *h, const int *fsize, int o, int d)
{
    int f = o ? h->face[h->twin[d]] : h->face[d];
    return (h->lcross[h->loop[d]] * 2 + h->layer[d]) * 64 + fsize[f];
}

/* The least code over the roots of least key, into best; whether some numbering reaching it
 * meets loop `wanted` before any other loop of cand (McKay's test). */
static int least_code(const Map *h, const unsigned char *cand, int wanted)
{
    static int fsize[MAXD];
    int low = 1 << 30, have = 0, accepted = 0;
    for (int f = 0; f < h->nf; f++) fsize[f] = h->fstart[f + 1] - h->fstart[f];
    for (int o = 0; o < 2; o++)
        for (int d = 0; d < h->D; d++) { int k = root_key(h, fsize, o, d); if (k < low) low = k; }
    for (int o = 0; o < 2; o++)
        for (int d = 0; d < h->D; d++) {
            if (root_key(h, fsize, o, d) != low) continue;
            int first, r = code_from(h, o, d, have, cand, &first);
            if (r < 0) continue;
            if (r > 0) { memcpy(best, code, sizeof(int) * (size_t)h->D); have = 1; accepted = 0; }
            if (first == wanted) accepted = 1;
        }
    return accepted;
}

/* Parity union-find over loops: s_a * s_b = want; 0 when the sets already force the other. */
static int relate(int *up, int *par, int a, int b, int want)
{
    int pa = 1, pb = 1;
    while (up[a] != a) { pa *= par[a]; a = up[a]; }
    while (up[b] != b) { pb *= par[b]; b = up[b]; }
    if (a == b) return pa * pb == want;
    up[a] = b;
    par[a] = pa * pb * want;
    return 1;
}

/* torus.orientable: a parity system over the loops (s_l = +1 when the + side of loop l is on
 * the right of its reference walk, from its least dart): a face between two third-axis loops
 * lies on the + side of one and the - side of the other; along a third-axis loop, consecutive
 * crossings with one class of B cross in the same sense; along a loop of B, consecutive
 * crossings with the third axis likewise. */
static int sides_consistent(const Map *h)
{
    static int fwd[MAXD], up[MAXL], par[MAXL], seen[MAXL], other[MAXD], sense[MAXD];
    for (int d = 0; d < h->D; d++) fwd[d] = 0;
    for (int l = 0; l < h->nl; l++) { up[l] = l; par[l] = 1; seen[l] = 0; }
    for (int d = 0; d < h->D; d++) {
        if (fwd[d]) continue;
        int e = d;
        while (!fwd[e]) { fwd[e] = 1; fwd[h->twin[e]] = -1; e = rot4(rot4(h->twin[e])); }
    }
    for (int f = 0; f < h->nf; f++) {
        int third[3], k = 0;
        for (int i = h->fstart[f]; i < h->fstart[f + 1] && k < 3; i++)
            if (h->layer[h->fdart[i]]) third[k++] = h->fdart[i];
        if (k != 2 || h->loop[third[0]] == h->loop[third[1]]) continue;
        if (!relate(up, par, h->loop[third[0]], h->loop[third[1]], -fwd[third[0]] * fwd[third[1]])) return 0;
    }
    for (int d = 0; d < h->D; d++) {
        int l = h->loop[d];
        if (seen[l] || fwd[d] != 1) continue;
        seen[l] = 1;
        int n = 0, e = d, mine = h->klass[l] == THIRD;
        do {
            int o = rot4(e);
            other[n] = h->loop[o];
            sense[n++] = fwd[o] == 1 ? 1 : -1;
            e = rot4(rot4(h->twin[e]));
        } while (e != d);
        for (int i = 0; i < n; i++) {
            int j = i + 1 == n ? 0 : i + 1, k1 = h->klass[other[i]], k2 = h->klass[other[j]];
            if (k1 != k2 || (k1 == THIRD) == mine) continue;
            if (!relate(up, par, other[i], other[j], sense[i] * sense[j])) return 0;
        }
    }
    return 1;
}

/* A simple quad mesh: no face on both sides of an edge, no two faces sharing two edges. */
static int simple_quad_mesh(const Map *h)
{
    static unsigned char pair[MAXD / 4 * MAXD / 4];
    int nf = h->nf;
    if ((size_t)nf * nf > sizeof(pair)) return 0;
    memset(pair, 0, (size_t)nf * nf);
    for (int d = 0; d < h->D; d++) {
        int a = h->face[d], b = h->face[h->twin[d]];
        if (a == b || pair[a * nf + b]) return 0;
        pair[a * nf + b] = 1;
    }
    return 1;
}

/* The child the cycle path[0..n) makes: a crossing on each crossed edge (darts forward, left,
 * back, right counter-clockwise, forward along the crossed dart, left into the face it leaves),
 * chords from each crossing to the next through the faces; then the keep tests. */
static void close_cycle(Ctx *c, int n)
{
    const Map *p = &c->p;
    Map *h = &child;
    int V = p->D / 4;
    c->closed++;
    h->D = p->D + 4 * n;
    memcpy(h->twin, p->twin, sizeof(int) * (size_t)p->D);
    memcpy(h->layer, p->layer, (size_t)p->D);
    for (int i = 0; i < n; i++) {
        int v = V + i, y = c->path[i], t = p->twin[y];
        h->twin[y] = 4 * v + 2; h->twin[4 * v + 2] = y;
        h->twin[t] = 4 * v; h->twin[4 * v] = t;
        h->layer[4 * v] = h->layer[4 * v + 2] = 0;
        h->layer[4 * v + 1] = h->layer[4 * v + 3] = 1;
    }
    for (int i = 0; i < n; i++) {   /* out of crossing i, into crossing i + 1 (the last into 0) */
        int from = i == 0 ? 4 * V + 1 : 4 * (V + i) + 3;
        int to = i + 1 < n ? 4 * (V + i + 1) + 1 : 4 * V + 3;
        h->twin[from] = to; h->twin[to] = from;
    }
    map_faces(h);
    if (map_loops(h) < 0) { c->failed = 2; return; }
    for (int l = 0; l < h->nl; l++) h->klass[l] = -1;
    for (int d = 0; d < h->D; d++) {
        int l = h->loop[d];
        if (h->layer[d]) h->klass[l] = THIRD;
        else if (h->klass[l] < 0 && d < p->D) h->klass[l] = p->klass[p->loop[d]];
    }
    int needs = 0;
    static int lack[MAXL];
    for (int f = 0; f < h->nf; f++) needs += face_need2(h, f);
    int lacks = lacking(h, lack);
    int later = (needs + 1) / 2 > lacks ? (needs + 1) / 2 : lacks;
    if (h->D / 4 + later > c->limit) { c->bounded++; return; }
    if (!sides_consistent(h)) { c->inconsistent++; return; }
    int changes = 0;
    for (int i = 0; i < n; i++)
        changes += p->klass[p->loop[c->path[i]]] != p->klass[p->loop[c->path[(i + n - 1) % n]]];
    if (changes < 4) { c->straight++; return; }
    static unsigned char cand[MAXL];
    int fewest = 1 << 30, wanted = h->loop[4 * V + 1];
    for (int l = 0; l < h->nl; l++) if (h->klass[l] == THIRD && h->lcross[l] < fewest) fewest = h->lcross[l];
    for (int l = 0; l < h->nl; l++) cand[l] = h->klass[l] == THIRD && h->lcross[l] == fewest;
    if (!cand[wanted] || !least_code(h, cand, wanted)) { c->rejected++; return; }
    int target = needs == 0 && simple_quad_mesh(h), balanced = 1;
    for (int k = 0; k < 2; k++) balanced &= c->third_with[k] + c->with_class[k] >= c->base;
    balanced |= (lacks == 0) << 1;  /* flag 4: no loop of B lacks a third-axis crossing */
    uint16_t tw[MAXD];
    unsigned char ly[MAXD];
    for (int i = 0; i < h->D; i++) { tw[i] = (uint16_t)(best[i] >> 1); ly[i] = (unsigned char)(best[i] & 1); }
    PyObject *item = Py_BuildValue("(y#y#i)", (const char *)tw, (Py_ssize_t)(2 * h->D), (const char *)ly,
                                   (Py_ssize_t)h->D, target | balanced << 1);
    if (!item || PyList_Append(c->out, item) < 0) c->failed = 1;
    Py_XDECREF(item);
}

/* Twice the need of the piece of face f from its dart at index i to the one at index j
 * (cyclically, both included, each split by the cycle) closed by the new loop's chord: a
 * lower bound (a side whose other side is in the piece is not looked for). */
static int piece_need2(const Ctx *c, int f, int i, int j)
{
    static unsigned stamp[MAXL], now;
    const Map *p = &c->p;
    int a = p->fstart[f], s = p->fstart[f + 1] - a, count[3] = {0, 0, 1}, bad = 0, k = 0;
    now++;
    for (int x = i;; x = x + 1 == s ? 0 : x + 1) {
        int l = p->loop[p->fdart[a + x]];
        count[p->klass[l]]++;
        if (stamp[l] == now) bad = 1;
        stamp[l] = now;
        k++;
        if (x == j) break;
    }
    return layered_need(k + 1, count, bad);
}

/* The cycle is in face f, entered across dart `in` of f, after n crossings (path[0..n));
 * run2 is twice the needs of the faces that are not open (all but f and the end face). */
static void dfs(Ctx *c, int f, int in, int n, int run2)
{
    const Map *p = &c->p;
    if (c->failed) return;
    c->nodes++;
    if (n > c->fewest_third) return;
    int sum = c->base;
    for (int k = 0; k < 2; k++) {
        int w = c->third_with[k] + c->with_class[k];
        sum += w > c->base ? w : c->base;
    }
    if (sum > c->limit) return;
    int later = (run2 + 1) / 2 > c->deficit ? (run2 + 1) / 2 : c->deficit;
    if (c->pc + n + later > c->limit) { c->bounded++; return; }
    if (f == c->end_face) {
        int y0 = c->path[0], last = c->path[n - 1];
        int once = n <= 2 ? y0 < p->twin[y0] : edge_of(p->twin, c->path[1]) < edge_of(p->twin, last);
        if (once) {
            /* the closing chord cuts the end face in two: a lower bound on the child's bound
             * (pieces without the other-side test, the loops of B by the crossings drawn),
             * before building it */
            int a0 = p->fstart[f], i = p->fpos[in] - a0, j = p->fpos[p->twin[y0]] - a0;
            int child2 = run2 + piece_need2(c, f, i, j) + piece_need2(c, f, j, i);
            int least = (child2 + 1) / 2 > c->deficit ? (child2 + 1) / 2 : c->deficit;
            if (c->pc + n + least > c->limit) { c->closed++; c->bounded++; }
            else close_cycle(c, n);
        }
    }
    if (n >= c->budget || c->region[f] == c->end_region) return;
    int a = p->fstart[f], s = p->fstart[f + 1] - a, i = p->fpos[in] - a;
    for (int j = 0; j < s; j++) {
        int y = p->fdart[a + j];
        if (j == i || p->layer[y] || edge_of(p->twin, y) <= c->first_edge) continue;
        int t = p->twin[y], g = p->face[t], rg = c->region[g];
        if (c->visited[rg] || (rg == c->end_region && g != c->end_face)) continue;
        int next2 = run2 + piece_need2(c, f, i, j) + piece_need2(c, f, j, i) - (g == c->end_face ? 0 : c->need2[g]);
        int l = p->loop[y], k = p->klass[l], serves = c->met[l] < c->lack[l];
        c->path[n] = y;
        c->visited[rg] = 1;
        c->with_class[k]++;
        c->met[l]++;
        c->deficit -= serves;
        dfs(c, g, t, n + 1, next2);
        c->deficit += serves;
        c->met[l]--;
        c->with_class[k]--;
        c->visited[rg] = 0;
    }
}

/* Regions of B: faces joined across third-axis edges (union-find). */
static void regions(Ctx *c)
{
    static int up[MAXD];
    const Map *p = &c->p;
    for (int f = 0; f < p->nf; f++) up[f] = f;
    for (int d = 0; d < p->D; d++) {
        if (!p->layer[d]) continue;
        int a = p->face[d], b = p->face[p->twin[d]];
        while (up[a] != a) a = up[a] = up[up[a]];
        while (up[b] != b) b = up[b] = up[up[b]];
        if (a != b) up[a] = b;
    }
    for (int f = 0; f < p->nf; f++) {
        int a = f;
        while (up[a] != a) a = up[a];
        c->region[f] = a;
    }
}

/* B's bipartition (B is cellular, so its crossing graph is connected); -1 if it is not one. */
static int classes(Map *p)
{
    static int stack[MAXL];
    int top = 0, start = -1;
    for (int l = 0; l < p->nl; l++) p->klass[l] = -1;
    for (int d = 0; d < p->D; d++) if (p->layer[d]) p->klass[p->loop[d]] = THIRD;
    for (int l = 0; l < p->nl && start < 0; l++) if (p->klass[l] < 0) start = l;
    if (start < 0) return -1;
    p->klass[start] = 0;
    stack[top++] = start;
    while (top) {
        int l = stack[--top];
        for (int d = 0; d < p->D; d++) {
            if (p->loop[d] != l) continue;
            int m = p->loop[rot4(d)];
            if (p->klass[m] == THIRD) continue;
            if (p->klass[m] < 0) { p->klass[m] = 1 - p->klass[l]; stack[top++] = m; }
            else if (p->klass[m] == p->klass[l]) return -1;
        }
    }
    for (int l = 0; l < p->nl; l++) if (p->klass[l] < 0) return -1;
    return 0;
}

static PyObject *children(PyObject *self, PyObject *args)
{
    Py_buffer tb, lb;
    int limit;
    if (!PyArg_ParseTuple(args, "y*y*i", &tb, &lb, &limit)) return NULL;
    if (limit < 0 || limit > MAXD / 4) {  /* a child's arrays hold MAXD darts: four a crossing */
        PyBuffer_Release(&tb); PyBuffer_Release(&lb);
        return PyErr_Format(PyExc_ValueError, "a limit of %d crossings: the compiled search holds 0 to %d",
                            limit, MAXD / 4);
    }
    Ctx *c = &ctx;
    Map *p = &c->p;
    int D = (int)(tb.len / 2);
    const uint16_t *twin = tb.buf;
    const unsigned char *layer = lb.buf;
    int bad = tb.len % 2 || D < 4 || D % 4 || lb.len != D || D > MAXD / 2;
    for (int d = 0; d < D && !bad; d++)
        bad = twin[d] >= D || twin[d] == d || twin[twin[d]] != d || layer[d] > 1;
    if (!bad) {
        p->D = D;
        for (int d = 0; d < D; d++) { p->twin[d] = twin[d]; p->layer[d] = layer[d]; }
    }
    PyBuffer_Release(&tb);
    PyBuffer_Release(&lb);
    if (bad) return PyErr_Format(PyExc_ValueError, "not the twin and layer arrays of an arrangement");
    map_faces(p);
    if (p->nf != D / 4) return PyErr_Format(PyExc_ValueError, "the arrangement is not cellular on the torus");
    if (map_loops(p) < 0) return PyErr_Format(PyExc_ValueError, "a loop crosses itself (or more than %d loops)", MAXL);
    for (int d = 0; d < D; d++)
        if (p->layer[d] != p->layer[p->twin[d]] || p->layer[d] != p->layer[rot4(rot4(d))])
            return PyErr_Format(PyExc_ValueError, "a loop is not wholly in one layer");
    if (classes(p) < 0) return PyErr_Format(PyExc_ValueError, "the loops outside the third layer are not a bipartite arrangement");
    c->limit = limit;
    c->base = 0;
    c->pc = D / 4;
    c->budget = limit - c->pc;
    c->third_with[0] = c->third_with[1] = 0;
    for (int d = 0; d < D; d += 4) {  /* B's crossings, and the third axis's with each class */
        int k1 = p->klass[p->loop[d]], k2 = p->klass[p->loop[d + 1]];
        if (k1 == THIRD && k2 != THIRD) c->third_with[k2]++;
        if (k2 == THIRD && k1 != THIRD) c->third_with[k1]++;
        if (k1 != THIRD && k2 != THIRD) c->base++;
    }
    for (int l = 0; l < p->nl; l++) c->met[l] = 0;
    c->deficit = lacking(p, c->lack);
    c->fewest_third = 1 << 30;
    for (int l = 0; l < p->nl; l++) if (p->klass[l] == THIRD && p->lcross[l] < c->fewest_third) c->fewest_third = p->lcross[l];
    regions(c);
    c->total2 = 0;
    for (int f = 0; f < p->nf; f++) c->total2 += c->need2[f] = face_need2(p, f);
    c->nodes = c->closed = c->bounded = c->inconsistent = c->rejected = c->straight = 0;
    c->failed = 0;
    c->out = PyList_New(0);
    if (!c->out) return NULL;
    memset(c->visited, 0, (size_t)p->nf);
    for (int y0 = 0; y0 < D && !c->failed; y0++) {
        if (p->layer[y0]) continue;
        int a = p->face[y0], b = p->face[p->twin[y0]];
        c->first_edge = edge_of(p->twin, y0);
        c->end_face = b;
        c->end_region = c->region[b];
        int l0 = p->loop[y0], serves = c->lack[l0] > 0;
        c->path[0] = y0;
        c->with_class[0] = c->with_class[1] = 0;
        c->with_class[p->klass[l0]]++;
        c->met[l0]++;
        c->deficit -= serves;
        c->visited[c->region[a]] = 1;
        dfs(c, a, y0, 1, c->total2 - c->need2[a] - (b == a ? 0 : c->need2[b]));
        c->visited[c->region[a]] = 0;
        c->deficit += serves;
        c->met[l0]--;
    }
    if (c->failed) {
        Py_DECREF(c->out);
        if (c->failed == 2) return PyErr_Format(PyExc_ValueError, "a child with more than %d loops", MAXL);
        return NULL;
    }
    return Py_BuildValue("(N(LLLLLL))", c->out, c->nodes, c->closed, c->bounded, c->inconsistent, c->rejected,
                         c->straight);
}

/* layered_code(twin, layer): the canonical code of a layered arrangement (the least over roots
 * and both orientations of the breadth-first code of twins and layers, as children() uses it),
 * as bytes: equal exactly for isomorphic layered arrangements, mirror images identified. */
static PyObject *layered_code(PyObject *self, PyObject *args)
{
    Py_buffer tb, lb;
    (void)self;
    if (!PyArg_ParseTuple(args, "y*y*", &tb, &lb)) return NULL;
    Map *h = &child;
    int D = (int)(tb.len / 2);
    const uint16_t *twin = tb.buf;
    const unsigned char *layer = lb.buf;
    int bad = tb.len % 2 || D < 4 || D % 4 || lb.len != D || D > MAXD;
    for (int d = 0; d < D && !bad; d++) bad = twin[d] >= D || twin[d] == d || twin[twin[d]] != d || layer[d] > 1;
    if (!bad) {
        h->D = D;
        for (int d = 0; d < D; d++) { h->twin[d] = twin[d]; h->layer[d] = layer[d]; }
    }
    PyBuffer_Release(&tb);
    PyBuffer_Release(&lb);
    if (bad) return PyErr_Format(PyExc_ValueError, "not the twin and layer arrays of an arrangement");
    map_faces(h);
    if (map_loops(h) < 0) return PyErr_Format(PyExc_ValueError, "a loop crosses itself (or more than %d loops)", MAXL);
    static unsigned char none[MAXL];
    least_code(h, none, -1);
    uint16_t out[MAXD];
    for (int i = 0; i < D; i++) out[i] = (uint16_t)best[i];
    return PyBytes_FromStringAndSize((const char *)out, (Py_ssize_t)(2 * D));
}

/* ---- the first stage: arrangements with marked faces ------------------------------------------
 *
 * first_children(twin, marks, limit, colours) gives the canonical children of a state of the
 * marked search (torus.torus_children without layers and without the regions' bound): twin as
 * uint16 (four darts a crossing; empty for a single loop, when marks is 0 for the essential loop
 * and 1 for the one bounding a disc), marks as a list of (kind, dart) with kind "A" (an end of
 * the annulus face) or "H" (the face with the handle), colours 0 (any crossing graph) or 2 (a
 * bipartite one).  The curve is drawn arc by arc through the faces as in torus._Drawing, each
 * arc through a marked face in each of its kinds; a child is kept when it is within the limit
 * (its crossings plus half the marked faces' needs), colourable, and its new loop is the
 * canonical loop to delete (among loops whose deletion leaves it connected, those with fewest
 * crossings, the first met in the canonical numbering of the marked map).  Each child comes
 * once, as (canonical twin array, marks, flags): flags bit 0 when it is cellular, bit 1 when
 * moreover (two colours) the zones of each class split every loop of it. */

#define A_MARK 0
#define H_MARK 1
#define MAXL1 64
#define MAXM 8                /* marks: a piece of genus h with b boundaries adds h + b - 1 <= genus, so 2 genus at most */

typedef struct {
    int n;                    /* darts of the drawing: the parent's, then 2 per point or chord */
    int rot[MAXD];            /* the next dart counter-clockwise round its vertex */
    int irot[MAXD];           /* the next dart clockwise (rot's inverse) */
    int twin[MAXD];           /* the dart at the edge's other end */
    int loop[MAXD];           /* the parent loop a dart lies on; -1 on the curve */
    int nmarks;               /* the marked faces: on the torus none, one H, or two A (the annulus's ends) */
    int mkind[MAXM];          /* A_MARK or H_MARK (torus) */
    int mdart[MAXM];          /* a dart with the marked face on its left */
    int general;              /* genus 2 or more: the marks name pieces (mgen, mpiece), not kinds */
    int mgen[MAXM];           /* general: the genus of the piece the face bounds */
    int mpiece[MAXM];         /* general: the piece's id (one mark a boundary of the piece) */
    int nloops;               /* the parent's loops */
    int lcross[MAXL1];        /* per parent loop: its crossings */
    int deletable[MAXL1];     /* per parent loop: its deletion leaves the parent connected */
    int klass[MAXL1];         /* per parent loop: its class in the crossing graph's bipartition (2 colours) */
    int pc;                   /* the parent's crossings */
    int limit;                /* the most crossings a target may have */
    int budget;               /* limit - pc */
    int colours;              /* 2: keep bipartite crossing graphs; 0: any */
    int side;                 /* the class the curve crosses (-1: not yet; 2 colours only) */
    int met[MAXL1];           /* the curve's crossings with each parent loop */
    int crossed;              /* the parent loops the curve has crossed */
    int ban[2];               /* a single loop: the darts of the piece the curve may not cross */
    int edge[MAXD];           /* the parent edge a dart lies on (its lesser dart); -1 on the curve */
    int least;                /* the curve's start edge: it crosses no parent edge below it */
    unsigned stamp[MAXD];     /* face membership: stamp[d] == now for the darts of the face at hand */
    unsigned now;
    PyObject *out;            /* the children found: a list of (twin, marks, flags) */
    PyObject *seen;           /* the children listed (a child is drawn in several ways) */
    int failed;               /* a Python error is set (out of memory): stop */
    long long nodes;          /* steps of the curve drawn */
    long long closed;         /* curves closed */
    long long bounded;        /* branches or children over the limit */
    long long rejected;       /* children whose new loop is not the canonical one to delete */
    long long uncolourable;   /* children whose crossing graph the colours cannot colour */
} Draw;

static Draw dw;

typedef struct {              /* a child in canonical form's making */
    int D;                    /* darts: four a crossing */
    int nf;                   /* faces */
    int nl;                   /* loops */
    int nmarks;               /* marked faces, as in Draw */
    int mkind[MAXM];          /* A_MARK or H_MARK (torus) */
    int mdart[MAXM];          /* a dart with the marked face on its left */
    int general;              /* as in Draw */
    int mgen[MAXM];           /* general: the piece's genus and id, as in Draw */
    int mpiece[MAXM];
    int twin[MAXD];           /* the dart across the edge */
    int face[MAXD];           /* the face on a dart's left */
    int fsize[MAXD];          /* per face: its sides */
    int loop[MAXD];           /* the loop a dart lies on */
    int lcross[MAXL1];        /* per loop: its crossings */
    uint64_t adj[MAXL1];      /* per loop: the loops it crosses, one bit each */
    int marked[MAXD];         /* per face: 1 when marked */
} Kid;

static Kid kid;
static int mark_need(int kind) { return kind == H_MARK ? 2 : 1; }

static void sub1(Draw *w, int y, int *q1, int *q2)
{
    int t = w->twin[y], a = w->n, b = w->n + 1;
    w->n += 2;
    w->loop[a] = w->loop[b] = w->loop[y];
    w->edge[a] = w->edge[b] = w->edge[y];
    w->rot[a] = b; w->rot[b] = a; w->irot[a] = b; w->irot[b] = a;
    w->twin[y] = b; w->twin[b] = y; w->twin[a] = t; w->twin[t] = a;
    *q1 = a; *q2 = b;
}

static void unsub1(Draw *w, int y, int q1)
{
    int t = w->twin[q1];
    w->twin[y] = t; w->twin[t] = y;
    w->n -= 2;
}

static void chord1(Draw *w, int x, int y)
{
    int a = w->n, b = w->n + 1, nx, ny;
    w->n += 2;
    w->loop[a] = w->loop[b] = -1;
    w->edge[a] = w->edge[b] = -1;
    nx = w->rot[x]; w->rot[x] = a; w->rot[a] = nx; w->irot[a] = x; w->irot[nx] = a;
    ny = w->rot[y]; w->rot[y] = b; w->rot[b] = ny; w->irot[b] = y; w->irot[ny] = b;
    w->twin[a] = b; w->twin[b] = a;
}

static void unchord1(Draw *w, int x, int y)
{
    int a = w->n - 2, b = w->n - 1, nx, ny;
    ny = w->rot[b]; w->rot[y] = ny; w->irot[ny] = y;
    nx = w->rot[a]; w->rot[x] = nx; w->irot[nx] = x;
    w->n -= 2;
}

/* Stamps the face on the left of d; returns its darts in order in buf and their number. */
static int face1(Draw *w, int d, int *buf)
{
    int k = 0, e = d;
    w->now++;
    do { w->stamp[e] = w->now; buf[k++] = e; e = w->irot[w->twin[e]]; } while (e != d);
    return k;
}

static int in_face(Draw *w, int d, int x)
{
    int e = d;
    do { if (e == x) return 1; e = w->irot[w->twin[e]]; } while (e != d);
    return 0;
}

/* Twice the crossings the pieces of the marks still need (cuts.pieces_need): a piece of genus h
 * with b boundaries, 2 (2h + b - 1); a piece with a face marked in ``open`` (one flag a mark, or
 * NULL for none) is left aside. */
static int pieces_need1(int nmarks, const int *gen, const int *piece, const int *open)
{
    int total = 0;
    for (int k = 0; k < nmarks; k++) {
        int first = 1, b = 0, skip = 0;
        for (int j = 0; j < nmarks; j++) {
            if (piece[j] != piece[k]) continue;
            if (j < k) first = 0;
            b++;
            if (open && open[j]) skip = 1;
        }
        if (first && !skip) total += 2 * (2 * gen[k] + b - 1);
    }
    return total;
}

/* Twice the crossings the marked faces still need, those holding x or end aside (genus 2 or
 * more: the pieces with such a face). */
static int needs1(Draw *w, int x, int end)
{
    int total = 0, open[MAXM];
    for (int k = 0; k < w->nmarks; k++) {
        open[k] = in_face(w, w->mdart[k], x) || in_face(w, w->mdart[k], end);
        if (!w->general && !open[k]) total += mark_need(w->mkind[k]);
    }
    if (w->general) total = pieces_need1(w->nmarks, w->mgen, w->mpiece, open);
    return total;
}

static int kid_code(Kid *h, int o, int r, int have_best, const unsigned char *cand, int *first, int *mcode)
{
    int cnt = 0, smaller = !have_best;
    for (int d = 0; d < h->D; d++) num[d] = -1;
    *first = -1;
#define VISIT(t0) do { int t_ = (t0); for (int j_ = 0; j_ < 4; j_++) { num[t_] = cnt; order[cnt++] = t_; \
        t_ = o ? irot4(t_) : rot4(t_); } } while (0)
    VISIT(r);
    for (int i = 0; i < h->D; i++) {
        int d = order[i], t = h->twin[d];
        if (*first < 0 && cand[h->loop[d]]) *first = h->loop[d];
        if (num[t] < 0) VISIT(t);
        code[i] = num[t];
        if (!smaller) {
            if (code[i] > best[i]) return -1;
            if (code[i] < best[i]) smaller = 1;
        }
    }
#undef VISIT
    /* the marked faces, each by its least dart number (in the mirror image, a face's darts
     * are rot of the original's), then kind; sorted */
    int lows[MAXM];
    for (int k = 0; k < h->nmarks; k++) {
        int low = 1 << 30, d = h->mdart[k], e = d;
        do { int g = o ? rot4(e) : e; if (num[g] < low) low = num[g]; e = irot4(h->twin[e]); } while (e != d);
        lows[k] = low;
        mcode[k] = 2 * low + h->mkind[k];
    }
    if (h->general) {
        /* (least number, genus, the piece's rank by the least number of its boundaries) */
        for (int k = 0; k < h->nmarks; k++) {
            int glow = lows[k], rank = 0;
            for (int j = 0; j < h->nmarks; j++) if (h->mpiece[j] == h->mpiece[k] && lows[j] < glow) glow = lows[j];
            for (int j = 0; j < h->nmarks; j++) {
                int first = 1, jlow = lows[j];
                for (int i = 0; i < h->nmarks; i++) {
                    if (h->mpiece[i] != h->mpiece[j]) continue;
                    if (i < j) first = 0;
                    if (lows[i] < jlow) jlow = lows[i];
                }
                if (first && jlow < glow) rank++;
            }
            mcode[k] = (lows[k] * 8 + h->mgen[k]) * 8 + rank;
        }
    }
    for (int k = 1; k < h->nmarks; k++)  /* sorted */
        for (int j = k; j > 0 && mcode[j - 1] > mcode[j]; j--) { int t = mcode[j]; mcode[j] = mcode[j - 1]; mcode[j - 1] = t; }
    if (!smaller)
        for (int k = 0; k < h->nmarks; k++) {
            if (mcode[k] > best[h->D + k]) return -1;
            if (mcode[k] < best[h->D + k]) { smaller = 1; break; }
        }
    return smaller;
}

static int connected_without1(const Kid *h, int skip)
{
    uint64_t all = 0, seen, frontier;
    for (int l = 0; l < h->nl; l++) if (l != skip) all |= (uint64_t)1 << l;
    if (!all) return 1;
    seen = frontier = all & -all;
    while (frontier) {
        uint64_t next = 0;
        for (int l = 0; l < h->nl; l++) if (frontier >> l & 1) next |= h->adj[l];
        next &= all & ~seen;
        seen |= next;
        frontier = next;
    }
    return seen == all;
}

/* Whether the crossing graph is bipartite; if so, side holds each loop's class. */
static int bipartite(const Kid *h, int *side)
{
    int stack[MAXL1], top = 0;
    for (int l = 0; l < h->nl; l++) side[l] = -1;
    for (int s = 0; s < h->nl; s++) {
        if (side[s] >= 0) continue;
        side[s] = 0;
        stack[top++] = s;
        while (top) {
            int l = stack[--top];
            for (int m = 0; m < h->nl; m++) {
                if (!(h->adj[l] >> m & 1)) continue;
                if (side[m] < 0) { side[m] = 1 - side[l]; stack[top++] = m; }
                else if (side[m] == side[l]) return 0;
            }
        }
    }
    return 1;
}

static int zone_find(int *up, int f)
{
    while (up[f] != f) { up[f] = up[up[f]]; f = up[f]; }
    return f;
}

/* Whether, for each class of the bipartition (side, from bipartite), every loop of it has two
 * different zones on its sides, the zones being the components left when the class's loops are
 * cut away (cuts.zones_split_every_loop, its twin). */
static int zones_split(const Kid *h, const int *side)
{
    int up[MAXD];
    for (int cls = 0; cls < 2; cls++) {
        for (int f = 0; f < h->nf; f++) up[f] = f;
        for (int d = 0; d < h->D; d++)
            if (side[h->loop[d]] != cls) {
                int a = zone_find(up, h->face[d]), b = zone_find(up, h->face[h->twin[d]]);
                if (a != b) up[a] = b;
            }
        for (int d = 0; d < h->D; d++)
            if (side[h->loop[d]] == cls && zone_find(up, h->face[d]) == zone_find(up, h->face[h->twin[d]]))
                return 0;
    }
    return 1;
}

/* The closed curve's child: points of degree 2 smoothed away, four darts a crossing; the keep
 * tests; the child in canonical numbering appended to the output. */
static void emit1(Draw *w)
{
    static int id[MAXD], orbit[8];
    Kid *h = &kid;
    int D = 0, curve = -1;
    w->closed++;
    for (int d = 0; d < w->n; d++) id[d] = -2;
    for (int d = 0; d < w->n; d++) {
        if (id[d] != -2) continue;
        int k = 0, e = d;
        do { if (k < 8) orbit[k] = e; k++; e = w->rot[e]; } while (e != d);
        if (k == 4) for (int j = 0; j < 4; j++) id[orbit[j]] = D++;
        else { e = d; do { id[e] = -1; e = w->rot[e]; } while (e != d); }
    }
    if (D > MAXD) { w->failed = 2; return; }
    h->D = D;
    for (int d = 0; d < w->n; d++) {
        if (id[d] < 0) continue;
        int t = w->twin[d];
        while (id[t] < 0) t = w->twin[w->rot[t]];
        h->twin[id[d]] = id[t];
        if (curve < 0 && w->loop[d] < 0) curve = id[d];
    }
    h->nmarks = w->nmarks;
    h->general = w->general;
    for (int k = 0; k < w->nmarks; k++) {
        int e = w->mdart[k];
        while (id[e] < 0) e = w->irot[w->twin[e]];
        h->mkind[k] = w->mkind[k];
        h->mgen[k] = w->mgen[k];
        h->mpiece[k] = w->mpiece[k];
        h->mdart[k] = id[e];
    }
    /* faces, loops */
    for (int d = 0; d < D; d++) h->face[d] = -1;
    h->nf = 0;
    for (int d = 0; d < D; d++) {
        if (h->face[d] >= 0) continue;
        int k = 0, e = d;
        do { h->face[e] = h->nf; k++; e = irot4(h->twin[e]); } while (e != d);
        h->marked[h->nf] = 0;
        h->fsize[h->nf++] = k;
    }
    for (int k = 0; k < h->nmarks; k++) h->marked[h->face[h->mdart[k]]] = 1;
    for (int d = 0; d < D; d++) h->loop[d] = -1;
    h->nl = 0;
    for (int d = 0; d < D; d++) {
        if (h->loop[d] >= 0) continue;
        if (h->nl >= MAXL1) { w->failed = 2; return; }
        int e = d;
        do { h->loop[e] = h->loop[h->twin[e]] = h->nl; e = rot4(rot4(h->twin[e])); } while (e != d);
        h->lcross[h->nl] = 0;
        h->adj[h->nl++] = 0;
    }
    for (int d = 0; d < D; d++) {
        int a = h->loop[d], b = h->loop[rot4(d)];
        if (a == b) { w->failed = 3; return; }
        h->lcross[a]++;
        h->adj[a] |= (uint64_t)1 << b;
    }
    for (int l = 0; l < h->nl; l++) h->lcross[l] /= 2;
    int needs = 0;
    for (int k = 0; k < h->nmarks; k++) needs += mark_need(h->mkind[k]);
    if (h->general) needs = pieces_need1(h->nmarks, h->mgen, h->mpiece, NULL);
    if (D / 4 + (needs + 1) / 2 > w->limit) { w->bounded++; return; }
    static int side[MAXL1];   /* two colours: each loop's class */
    if (w->colours == 2 && !bipartite(h, side)) { w->uncolourable++; return; }
    static unsigned char cand[MAXL1];
    int fewest = 1 << 30, wanted = h->loop[curve];
    for (int l = 0; l < h->nl; l++) {
        cand[l] = (unsigned char)connected_without1(h, l);
        if (cand[l] && h->lcross[l] < fewest) fewest = h->lcross[l];
    }
    for (int l = 0; l < h->nl; l++) cand[l] = cand[l] && h->lcross[l] == fewest;
    if (!cand[wanted]) { w->rejected++; return; }
    /* the least code over the roots of least key, and McKay's test */
    int low = 1 << 30, have = 0, accepted = 0, mcode[MAXM];
    for (int o = 0; o < 2; o++)
        for (int d = 0; d < D; d++) {
            int f = o ? h->face[h->twin[d]] : h->face[d];
            int key = ((h->lcross[h->loop[d]] * 64 + (h->fsize[f] < 63 ? h->fsize[f] : 63)) * 2) + h->marked[f];
            if (key < low) low = key;
        }
    for (int o = 0; o < 2; o++)
        for (int d = 0; d < D; d++) {
            int f = o ? h->face[h->twin[d]] : h->face[d];
            int key = ((h->lcross[h->loop[d]] * 64 + (h->fsize[f] < 63 ? h->fsize[f] : 63)) * 2) + h->marked[f];
            if (key != low) continue;
            int first, r = kid_code(h, o, d, have, cand, &first, mcode);
            if (r < 0) continue;
            if (r > 0) {
                memcpy(best, code, sizeof(int) * (size_t)D);
                for (int k = 0; k < h->nmarks; k++) best[D + k] = mcode[k];
                have = 1; accepted = 0;
            }
            if (first == wanted) accepted = 1;
        }
    if (!accepted) { w->rejected++; return; }
    uint16_t tw[MAXD + MAXM];
    for (int i = 0; i < D; i++) tw[i] = (uint16_t)best[i];
    for (int k = 0; k < h->nmarks; k++) tw[D + k] = (uint16_t)best[D + k];
    /* one of each child: the list would otherwise hold every way it was drawn */
    PyObject *key = PyBytes_FromStringAndSize((const char *)tw, (Py_ssize_t)(2 * (D + h->nmarks)));
    int listed = key ? PySet_Contains(w->seen, key) : -1;
    if (listed == 0 && PySet_Add(w->seen, key) < 0) listed = -1;
    Py_XDECREF(key);
    if (listed < 0) { w->failed = 1; return; }
    if (listed) return;
    PyObject *marks = PyList_New(h->nmarks);
    if (!marks) { w->failed = 1; return; }
    for (int k = 0; k < h->nmarks; k++) {
        PyObject *m;
        if (h->general) {     /* ("g<genus>.<piece's rank>", least number) */
            char kind[24];
            snprintf(kind, sizeof kind, "g%d.%d", (best[D + k] >> 3) & 7, best[D + k] & 7);
            m = Py_BuildValue("(si)", kind, best[D + k] >> 6);
        } else
            m = Py_BuildValue("(si)", (best[D + k] & 1) ? "H" : "A", best[D + k] >> 1);
        if (!m) { Py_DECREF(marks); w->failed = 1; return; }
        PyList_SET_ITEM(marks, k, m);
    }
    /* bit 0: cellular; bit 1 (two colours, cellular): the zones split every loop */
    int flags = h->nmarks == 0 ? 1 | (w->colours == 2 && zones_split(h, side) ? 2 : 0) : 0;
    PyObject *item = Py_BuildValue("(y#Ni)", (const char *)tw, (Py_ssize_t)(2 * D), marks, flags);
    if (!item || PyList_Append(w->out, item) < 0) w->failed = 1;
    Py_XDECREF(item);
}

static void dfs1(Draw *w, int x, int end, int cr);

static void go1(Draw *w, int then, int end, int cr)
{
    if (then < 0) emit1(w);
    else dfs1(w, then, end, cr);
}

static void add_mark(Draw *w, int gen, int piece, int dart)
{
    w->mgen[w->nmarks] = gen; w->mpiece[w->nmarks] = piece; w->mdart[w->nmarks] = dart; w->nmarks++;
}

/* chords1 through a piece of genus h with b boundaries (mark mi on the face of x), on a surface
 * of genus 2 or more (stages._ChildSearch._piece_chords, its twin): to another boundary, one
 * piece with one boundary fewer; back to its own, either one piece of genus h - 1 with one
 * boundary more, or two pieces of genus h1 and h - h1 sharing the other boundaries (a piece of
 * genus 0 with one boundary is a disc). */
static void piece_chords1(Draw *w, int x, int y, int then, int end, int cr, int mi)
{
    int snm = w->nmarks, sg[MAXM], sp[MAXM], sd[MAXM], others[MAXM], no = 0, fresh = 0;
    int h = w->mgen[mi], piece = w->mpiece[mi];
    for (int k = 0; k < snm; k++) {
        sg[k] = w->mgen[k]; sp[k] = w->mpiece[k]; sd[k] = w->mdart[k];
        if (sp[k] >= fresh) fresh = sp[k] + 1;
        if (sp[k] == piece && k != mi) others[no++] = k;
    }
#define RESTORE() do { w->nmarks = snm; for (int k_ = 0; k_ < snm; k_++) { \
        w->mgen[k_] = sg[k_]; w->mpiece[k_] = sp[k_]; w->mdart[k_] = sd[k_]; } } while (0)
#define KEEP_REST() do { w->nmarks = 0; for (int k_ = 0; k_ < snm; k_++) \
        if (sp[k_] != piece) add_mark(w, sg[k_], sp[k_], sd[k_]); } while (0)
    if (!in_face(w, x, y)) { /* to another boundary of the piece: the two become one */
        int mj = -1;
        for (int j = 0; j < no; j++) if (in_face(w, sd[others[j]], y)) mj = others[j];
        chord1(w, x, y);
        int a = w->n - 2;
        KEEP_REST();
        for (int j = 0; j < no; j++) if (others[j] != mj) add_mark(w, h, piece, sd[others[j]]);
        if (h || no > 1) add_mark(w, h, piece, a);  /* else now a disc */
        go1(w, then, end, cr);
        RESTORE();
        unchord1(w, x, y);
        return;
    }
    if (h >= 1) {            /* not separating */
        chord1(w, x, y);
        int a = w->n - 2, b = w->n - 1;
        KEEP_REST();
        for (int j = 0; j < no; j++) add_mark(w, h - 1, fresh, sd[others[j]]);
        add_mark(w, h - 1, fresh, a);
        add_mark(w, h - 1, fresh, b);
        go1(w, then, end, cr);
        RESTORE();
        unchord1(w, x, y);
        if (w->failed) return;
    }
    for (int h1 = 0; h1 <= h; h1++)
        for (int mask = 0; mask < 1 << no; mask++) {
            chord1(w, x, y);
            int a = w->n - 2, b = w->n - 1;
            KEEP_REST();
            if (h1 || mask) {
                for (int j = 0; j < no; j++) if (mask >> j & 1) add_mark(w, h1, fresh, sd[others[j]]);
                add_mark(w, h1, fresh, a);
            }
            if (h - h1 || mask != (1 << no) - 1) {
                for (int j = 0; j < no; j++) if (!(mask >> j & 1)) add_mark(w, h - h1, fresh + 1, sd[others[j]]);
                add_mark(w, h - h1, fresh + 1, b);
            }
            go1(w, then, end, cr);
            RESTORE();
            unchord1(w, x, y);
            if (w->failed) return;
        }
#undef RESTORE
#undef KEEP_REST
}

/* Draws the chord from x to y in each way the faces allow; after each, emits the child
 * (then = -1) or continues the curve from dart `then` with cr crossings. */
static void chords1(Draw *w, int x, int y, int then, int end, int cr)
{
    int mi = -1, e = x, skind[2], sdart[2], snm = w->nmarks;
    for (int k = 0; k < 2; k++) { skind[k] = w->mkind[k]; sdart[k] = w->mdart[k]; }
    do {
        for (int k = 0; k < w->nmarks; k++) if (w->mdart[k] == e) mi = k;
        e = w->irot[w->twin[e]];
    } while (e != x);
    if (w->general && mi >= 0) { piece_chords1(w, x, y, then, end, cr, mi); return; }
    int same = in_face(w, x, y);
    int kind = mi < 0 ? -1 : w->mkind[mi];
    int options = !same ? 1 : kind < 0 ? 1 : kind == H_MARK ? 3 : 2;
    for (int opt = 0; opt < options; opt++) {
        chord1(w, x, y);
        int a = w->n - 2, b = w->n - 1;
        if (!same) w->nmarks = 0;  /* across the annulus: every face a disc */
        else if (kind >= 0) {
            if (opt == 2) { w->nmarks = 2; w->mkind[0] = w->mkind[1] = A_MARK; w->mdart[0] = a; w->mdart[1] = b; }
            else w->mdart[mi] = opt == 0 ? a : b;
        }
        if (then < 0) emit1(w);
        else dfs1(w, then, end, cr);
        w->nmarks = snm;
        for (int k = 0; k < 2; k++) { w->mkind[k] = skind[k]; w->mdart[k] = sdart[k]; }
        unchord1(w, x, y);
        if (w->failed) return;
    }
}

static void dfs1(Draw *w, int x, int end, int cr)
{
    static int fbuf[64][MAXD];
    int *targets = fbuf[cr < 64 ? cr : 63];
    if (w->failed) return;
    w->nodes++;
    for (int l = 0; l < w->nloops; l++)
        if (w->deletable[l] && w->crossed > (w->met[l] > 0) && cr > w->lcross[l] + w->met[l]) return;
    if (w->pc + cr + (needs1(w, x, end) + 1) / 2 > w->limit) { w->bounded++; return; }
    int k = face1(w, x, targets), mi = -1;
    for (int j = 0; j < w->nmarks; j++) if (w->stamp[w->mdart[j]] == w->now) mi = j;
    if (mi >= 0 && w->general) {  /* the piece's other boundaries */
        int here = mi;
        for (int j = 0; j < w->nmarks; j++)
            if (j != here && w->mpiece[j] == w->mpiece[here]) k += face1(w, w->mdart[j], targets + k);
    } else if (mi >= 0 && w->mkind[mi] == A_MARK) {
        int other = w->mdart[1 - mi];
        k += face1(w, other, targets + k);
    }
    int closable = 0;
    for (int j = 0; j < k; j++) if (targets[j] == end) closable = 1;
    if (closable) chords1(w, x, end, -1, end, cr);
    if (cr >= w->budget || w->n + 8 > MAXD || cr >= 63) return;
    for (int j = 0; j < k && !w->failed; j++) {
        int y = targets[j], lp = w->loop[y];
        if (lp < 0 || y == w->ban[0] || y == w->ban[1] || w->edge[y] < w->least) continue;
        if (w->colours == 2 && w->side >= 0 && w->klass[lp] != w->side) continue;
        int q1, q2, side = w->side;
        sub1(w, y, &q1, &q2);
        if (!w->met[lp]++) w->crossed++;
        if (w->colours == 2) w->side = w->klass[lp];
        chords1(w, x, q1, q2, end, cr + 1);
        w->side = side;
        if (!--w->met[lp]) w->crossed--;
        unsub1(w, y, q1);
    }
}

/* Marks "g<genus>.<piece>" (genus 2 or more): each piece's genus, its boundaries' count within
 * the surface's genus; returns their number, or -1. */
static int parse_piece_marks(PyObject *marks, Draw *w, int D, int genus)
{
    if (!PyList_Check(marks) && !PyTuple_Check(marks)) return -1;
    Py_ssize_t m = PySequence_Size(marks);
    if (m < 0 || m > MAXM) return -1;
    for (Py_ssize_t k = 0; k < m; k++) {
        PyObject *it = PySequence_GetItem(marks, k);
        const char *s;
        int d, g, p, used = 0;
        int ok = it && PyArg_ParseTuple(it, "si", &s, &d);
        Py_XDECREF(it);
        if (!ok) { PyErr_Clear(); return -1; }
        if (d < 0 || d >= D || sscanf(s, "g%d.%d%n", &g, &p, &used) != 2 || s[used] || g < 0 || g > genus || p < 0
            || p > 1000) return -1;
        w->mgen[k] = g; w->mpiece[k] = p; w->mdart[k] = d; w->mkind[k] = 0;
    }
    for (Py_ssize_t k = 0; k < m; k++)
        for (Py_ssize_t j = 0; j < m; j++)
            if (w->mpiece[j] == w->mpiece[k] && w->mgen[j] != w->mgen[k]) return -1;
    return (int)m;
}

static int parse_marks(PyObject *marks, int *kind, int *dart, int D)
{
    if (!PyList_Check(marks) && !PyTuple_Check(marks)) return -1;
    Py_ssize_t m = PySequence_Size(marks);
    if (m != 0 && m != 1 && m != 2) return -1;
    for (Py_ssize_t k = 0; k < m; k++) {
        PyObject *it = PySequence_GetItem(marks, k);
        const char *s;
        int d;
        int ok = it && PyArg_ParseTuple(it, "si", &s, &d);
        Py_XDECREF(it);
        if (!ok) { PyErr_Clear(); return -1; }
        if (d < 0 || d >= D || (s[0] != 'A' && s[0] != 'H') || s[1]) return -1;
        kind[k] = s[0] == 'H' ? H_MARK : A_MARK;
        dart[k] = d;
    }
    if ((m == 1 && kind[0] != H_MARK) || (m == 2 && (kind[0] != A_MARK || kind[1] != A_MARK))) return -1;
    return (int)m;
}

static PyObject *first_children(PyObject *self, PyObject *args)
{
    Py_buffer tb;
    PyObject *marks;
    int limit, colours, genus = 1;
    (void)self;
    if (!PyArg_ParseTuple(args, "y*Oii|i", &tb, &marks, &limit, &colours, &genus)) return NULL;
    if (genus < 1 || genus > MAXM / 2) {
        PyBuffer_Release(&tb);
        return PyErr_Format(PyExc_ValueError, "genus %d: the compiled search takes 1 to %d", genus, MAXM / 2);
    }
    if (limit < 0 || limit > MAXD / 4) {
        PyBuffer_Release(&tb);
        return PyErr_Format(PyExc_ValueError, "a limit of %d crossings: the compiled search holds 0 to %d",
                            limit, MAXD / 4);
    }
    Draw *w = &dw;
    int D = (int)(tb.len / 2), bad = tb.len % 2 || D % 4 || D > MAXD / 4 || (colours != 0 && colours != 2);
    const uint16_t *twin = tb.buf;
    for (int d = 0; d < D && !bad; d++) bad = twin[d] >= D || twin[d] == d || twin[twin[d]] != d;
    if (!bad) for (int d = 0; d < D; d++) w->twin[d] = twin[d];
    PyBuffer_Release(&tb);
    if (bad) return PyErr_Format(PyExc_ValueError, "not the twin array of a 4-regular map (or colours not 0 or 2)");
    w->colours = colours;
    w->limit = limit;
    w->general = genus >= 2;
    w->nodes = w->closed = w->bounded = w->rejected = w->uncolourable = 0;
    w->failed = 0;
    w->crossed = 0;
    w->side = -1;
    memset(w->met, 0, sizeof(w->met));
    if (D == 0) {             /* a single loop: a point of degree 2 on it */
        long root = PyLong_AsLong(marks);
        long roots = genus == 1 ? 2 : 2 + genus / 2;
        if (PyErr_Occurred() || root < 0 || root >= roots)
            return PyErr_Format(PyExc_ValueError, "a single loop is 0 to %ld (drawing.roots)", roots - 1);
        w->n = 2;
        w->rot[0] = w->irot[0] = 1; w->rot[1] = w->irot[1] = 0;
        w->twin[0] = 1; w->twin[1] = 0;
        w->loop[0] = w->loop[1] = 0;
        w->edge[0] = w->edge[1] = 0;
        w->nmarks = 0;
        if (genus >= 2) {     /* drawing.roots: not separating, then a piece of genus h cut off */
            if (root == 0) { add_mark(w, genus - 1, 0, 0); add_mark(w, genus - 1, 0, 1); }
            else if (root == 1) add_mark(w, genus, 0, 1);
            else { add_mark(w, (int)root - 1, 0, 0); add_mark(w, genus - (int)root + 1, 1, 1); }
        } else if (root == 0) { w->nmarks = 2; w->mkind[0] = w->mkind[1] = A_MARK; w->mdart[0] = 0; w->mdart[1] = 1; }
        else { w->nmarks = 1; w->mkind[0] = H_MARK; w->mdart[0] = 1; }
        w->nloops = 1; w->lcross[0] = 0; w->deletable[0] = 0; w->klass[0] = 0;
        w->pc = 0;
    } else {
        int m = genus >= 2 ? parse_piece_marks(marks, w, D, genus) : parse_marks(marks, w->mkind, w->mdart, D);
        if (m < 0 && genus >= 2)
            return PyErr_Format(PyExc_ValueError, "marks are (\"g<genus>.<piece>\", dart), at most %d", MAXM);
        if (m < 0) return PyErr_Format(PyExc_ValueError, "marks are none, one (\"H\", dart) or two (\"A\", dart)");
        w->nmarks = m;
        w->n = D;
        for (int d = 0; d < D; d++) { w->rot[d] = rot4(d); w->irot[d] = irot4(d); }
        Kid *h = &kid;        /* the parent's loops, crossing graph, deletable loops, classes */
        h->D = D;
        memcpy(h->twin, w->twin, sizeof(int) * (size_t)D);
        for (int d = 0; d < D; d++) h->loop[d] = -1;
        h->nl = 0;
        for (int d = 0; d < D; d++) {
            if (h->loop[d] >= 0) continue;
            if (h->nl >= MAXL1) return PyErr_Format(PyExc_ValueError, "more than %d loops", MAXL1);
            int e = d;
            do { h->loop[e] = h->loop[h->twin[e]] = h->nl; e = rot4(rot4(h->twin[e])); } while (e != d);
            h->lcross[h->nl] = 0;
            h->adj[h->nl++] = 0;
        }
        for (int d = 0; d < D; d++) {
            if (h->loop[d] == h->loop[rot4(d)]) return PyErr_Format(PyExc_ValueError, "a loop crosses itself");
            h->lcross[h->loop[d]]++;
            h->adj[h->loop[d]] |= (uint64_t)1 << h->loop[rot4(d)];
        }
        w->nloops = h->nl;
        for (int l = 0; l < h->nl; l++) {
            w->lcross[l] = h->lcross[l] / 2;
            w->deletable[l] = connected_without1(h, l);
            w->klass[l] = -1;
        }
        for (int d = 0; d < D; d++) {
            w->loop[d] = h->loop[d];
            w->edge[d] = d < w->twin[d] ? d : w->twin[d];
        }
        if (colours == 2) {   /* the parent's bipartition (its crossing graph is connected) */
            int stack[MAXL1], top = 0;
            w->klass[0] = 0;
            stack[top++] = 0;
            while (top) {
                int l = stack[--top];
                for (int k = 0; k < h->nl; k++) {
                    if (!(h->adj[l] >> k & 1)) continue;
                    if (w->klass[k] < 0) { w->klass[k] = 1 - w->klass[l]; stack[top++] = k; }
                    else if (w->klass[k] == w->klass[l])
                        return PyErr_Format(PyExc_ValueError, "the crossing graph is not bipartite");
                }
            }
        }
        w->pc = D / 4;
    }
    w->budget = limit - w->pc;
    w->out = PyList_New(0);
    if (!w->out) return NULL;
    w->seen = PySet_New(NULL);
    if (!w->seen) { Py_DECREF(w->out); return NULL; }
    int n0 = w->n;
    /* The curve starts at a point of an edge and enters the face on the left of the edge's
     * dart y0.  One dart an edge: a curve through the edge, walked the other way round, enters
     * the face on the twin's left, and it is the same loop.  And the least edge it crosses:
     * the curve is drawn from there only (w->least), not from every edge it crosses.  Both
     * hold because every test on the way is a test of the whole curve (a branch cut is a curve
     * that would fail at its end, whichever way and wherever it was begun). */
    for (int y0 = 0; y0 < n0 && !w->failed; y0++) {
        if (w->twin[y0] < y0) continue;
        int p1, p2, lp = w->loop[y0];
        sub1(w, y0, &p1, &p2);
        /* A single loop: its point of degree 2 is only a mark of where the loop is, and it may
         * lie in any gap between the curve's points; in the gap before the first one (the
         * piece from y0 to p2 is never crossed), so each curve is drawn once a start, not once
         * a start and a gap. */
        w->ban[0] = w->ban[1] = -1;
        w->least = y0;
        if (D == 0) { w->ban[0] = y0; w->ban[1] = p2; }
        w->met[lp] = 1;
        w->crossed = 1;
        w->side = colours == 2 ? w->klass[lp] : -1;
        dfs1(w, p1, p2, 1);
        w->met[lp] = 0;
        w->crossed = 0;
        unsub1(w, y0, p1);
    }
    Py_CLEAR(w->seen);
    if (w->failed) {
        Py_DECREF(w->out);
        if (w->failed == 1) return NULL;
        return PyErr_Format(PyExc_ValueError, w->failed == 2 ? "a child too large" : "a loop crosses itself");
    }
    return Py_BuildValue("(N(LLLLL))", w->out, w->nodes, w->closed, w->bounded, w->rejected, w->uncolourable);
}

static PyMethodDef methods[] = {
    {"children", children, METH_VARARGS,
     "children(twin, layer, limit) -> (children, (paths drawn, cycles closed, over the bound,\n"
     "third axis not orientable, not canonical, fewer than four runs)): the second-stage children of a layered torus\n"
     "arrangement (twin as uint16, layer as bytes, four darts a crossing), each as (canonical\n"
     "twin array, layer bytes, flags: 1 a target, 2 balanced, 4 no loop of B lacking), possibly repeated"},
    {"layered_code", layered_code, METH_VARARGS,
     "layered_code(twin, layer) -> the canonical code of a layered arrangement, as bytes"},
    {"first_children", first_children, METH_VARARGS,
     "first_children(twin, marks, limit, colours, genus=1) -> (children, (paths drawn, curves closed, over\n"
     "the bound, not canonical, not colourable)): the children of a state of the marked search (twin\n"
     "as uint16, four darts a crossing, with marks [(kind, dart)]; an empty twin with marks 0 or 1\n"
     "for the single loop, essential or not), colours 0 or 2, each as (canonical twin array, marks,\n"
     "is_cellular), possibly repeated"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_torus", NULL, -1, methods};

PyMODINIT_FUNC PyInit__torus(void) { return PyModule_Create(&module); }
