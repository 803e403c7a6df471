/* One step of the canonical construction of arrangements of simple closed curves
 * (polyloops/generate/loops/arrangements.py explains the method and proves the cuts).
 *
 * An arrangement is a connected 4-regular map on the sphere whose straight-ahead walks (its
 * loops) are simple closed curves; its faces are the regions, its vertices the crossings.
 * Darts carry `rot` (the next dart counter-clockwise around the origin) and `twin`; the face
 * on the left of d continues with irot(twin(d)).  A canonical arrangement numbers its darts
 * in blocks of four, one block a crossing, rot(4v + i) = 4v + (i + 1) % 4, so its `twin`
 * array alone is the arrangement.
 *
 * children(rot, twin, limit) draws every simple closed curve that crosses the parent at most
 * `limit` - (parent crossings) times, as a path that crosses one edge at a time and splits the
 * faces it passes, and returns each child that
 *   - can still grow into an arrangement with at most `limit` crossings whose regions have 3 to
 *     6 sides (the counting bound `need`) and, with cut 5, meet each loop at most once, and
 *   - has the new curve as its canonical loop to delete: among loops whose deletion leaves
 *     the arrangement connected, those with the fewest crossings, and of these the one met
 *     first in the canonical numbering (McKay's canonical construction path),
 * as its canonical twin array (uint16), with a flag telling whether the child is itself a
 * candidate (regions of 3 to 6 sides, no two regions sharing two edges or one region on both
 * sides of an edge, and with cut 5 no region with two sides on one loop).  A parent with two darts is the single loop, with one marker vertex.
 *
 * canonical(rot, twin) gives the canonical twin array and the candidate flag of one
 * arrangement.
 *
 * Not reentrant: the search keeps one static context and one static child, and runs with the
 * GIL held (it never releases it), so Python calls it one at a time per process; the catalog
 * parallelises over processes.  Names follow docs/catalog.md ("Cuts, with their proofs").
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdint.h>
#include <string.h>

#define MAXD 1024          /* darts while drawing: parent + 4 per new crossing */
#define MAXV (MAXD / 2)
#define MAXL 64            /* loops (a bit mask each) */

/* The search context, one parent at a time.  The module keeps one static context and one
 * static child (below), so it is not reentrant: Python calls it with the GIL held, one call
 * at a time per process (the catalog's workers are processes, not threads). */
typedef struct {
    /* the partial map being drawn: the parent's darts, then 2 per edge piece or chord added */
    int rot[MAXD];          /* next dart counter-clockwise around the origin */
    int irot[MAXD];         /* rot's inverse */
    int twin[MAXD];         /* the other dart of the edge */
    int origin[MAXD];       /* the vertex a dart leaves (crossings first, then the new points) */
    int parent_dart[MAXD];  /* the parent dart an edge piece lies along (-1 on the new curve) */
    unsigned char on_curve[MAXD];  /* 1 for the darts of the curve being drawn */
    int seen[MAXD];         /* a stamp per dart, for walks that visit each face once */
    int fsize[MAXD];        /* the number of corners of the face on the dart's left */
    int fneed2[MAXD];       /* twice the need the running bound counts for that face (cut 1's
                               need, or cut 5's when larger; open faces: not counted) */
    unsigned flabel[MAXD], next_label;  /* a label per face (on its darts); reset with each parent */
    int stamp;              /* the current value for seen[] */
    int n, nv, nv0;         /* darts, vertices now, vertices of the parent */
    int parent_edge[MAXD];  /* the lesser dart of the parent edge a parent dart lies on */
    unsigned char marker[MAXV];    /* a degree-2 vertex: the single loop's marker */
    int parent_crossings;   /* crossings of the parent (its vertices, markers aside) */
    int limit;              /* the corner budget of the whole search */
    int budget;             /* crossings the new curve may add: limit - parent_crossings */
    int first_edge;         /* the start edge: no edge below it in the numbering may be crossed */
    int near, near_twin;    /* the start edge's piece between its origin and the start: the
                               curve starts at its crossing nearest the origin, so it never
                               crosses that piece again */
    int loop_of[MAXD];      /* the parent loop a dart lies on */
    int nloops;             /* the parent's loops */
    int loop_crossings[MAXL];  /* crossings of each parent loop in the parent */
    int deletable[MAXL];    /* 1 when deleting the loop leaves the parent connected */
    uint64_t parent_adj[MAXL];  /* the parent loops each parent loop crosses, a bit each */
    uint64_t crossed;       /* the parent loops the curve being drawn has crossed, a bit each */
    int crossings_with[MAXL];  /* crossings of the curve being drawn with each parent loop */
    int colour_cut;         /* cut 4: drop children whose crossing graph is not 3-colourable */
    int meet_cut;           /* cut 5: a region must end meeting each loop at most once */
    PyObject *out;          /* the list of children found */
    int failed;             /* 1: a Python error is set; 2: a child with too many loops */
    long long nodes, closed, bounded, rejected, uncolourable, met_twice;  /* statistics: curves
                   drawn, closed, over the bound, not canonical, not 3-colourable, over cut 5's */
} Ctx;

static inline int need(int s)
{
    if (s < 3) return 3 - s;
    if (s > 6) return (s - 5) / 2;
    return 0;
}

static inline int max3(int a, int b, int c) { return a > b ? (a > c ? a : c) : (b > c ? b : c); }

/* Cut 2 of docs/catalog.md (the open faces' shares), doubled to stay in integers.  half2(s):
 * twice the least share of the later crossings that an open face of s sides needs where the
 * path leaves from one of its corners (one half-arc from the corner, then t arcs and x
 * crossings: t + x >= max(0, ceil((s - 9) / 2), 3 - s), share t + x + 1/2).  both2(s): the
 * same for the face holding both ends of the path, the lesser of closing at once (share t + x,
 * t + x >= max(0, ceil((s - 10) / 2), 4 - s)) and leaving and coming back (share t + x + 1,
 * t + x >= max(0, ceil((s - 12) / 2), 3 - s)).  need(s) is cut 1's need of a closed region. */
static inline int half2(int s) { return 2 * max3(0, s >= 9 ? (s - 8) / 2 : 0, 3 - s) + 1; }

static inline int both2(int s)
{
    int direct = 2 * max3(0, s >= 10 ? (s - 9) / 2 : 0, 4 - s);
    int around = 2 + 2 * max3(0, s >= 12 ? (s - 11) / 2 : 0, 3 - s);
    return direct < around ? direct : around;
}

static inline int fnext(const Ctx *c, int e) { return c->irot[c->twin[e]]; }

static void subdivide(Ctx *c, int e, int *e1, int *e2)
{
    int q = c->nv++, a = c->n, b = c->n + 1, te = c->twin[e];
    c->n += 2;
    c->rot[a] = b; c->rot[b] = a; c->irot[a] = b; c->irot[b] = a;
    c->twin[a] = e; c->twin[b] = te; c->origin[a] = q; c->origin[b] = q;
    c->on_curve[a] = 0; c->on_curve[b] = 0; c->parent_dart[a] = c->parent_dart[te]; c->parent_dart[b] = c->parent_dart[e];
    c->twin[e] = a; c->twin[te] = b;
    *e1 = a; *e2 = b;
}

static void unsubdivide(Ctx *c, int e, int e1)
{
    int te = c->twin[e1 + 1];
    c->twin[e] = te; c->twin[te] = e;
    c->n -= 2; c->nv--;
}

/* A chord from the origin of x (right after x, counter-clockwise) to the origin of y. */
static void chord(Ctx *c, int x, int y)
{
    int a = c->n, b = c->n + 1, rx = c->rot[x], ry = c->rot[y];
    c->n += 2;
    c->rot[a] = rx; c->rot[b] = ry; c->irot[a] = x; c->irot[b] = y;
    c->twin[a] = b; c->twin[b] = a; c->origin[a] = c->origin[x]; c->origin[b] = c->origin[y];
    c->on_curve[a] = 1; c->on_curve[b] = 1; c->parent_dart[a] = -1; c->parent_dart[b] = -1;
    c->rot[x] = a; c->irot[rx] = a; c->rot[y] = b; c->irot[ry] = b;
}

static void unchord(Ctx *c, int x, int y)
{
    int a = c->n - 2, b = c->n - 1, rx = c->rot[a], ry = c->rot[b];
    c->rot[x] = rx; c->irot[rx] = x; c->rot[y] = ry; c->irot[ry] = y;
    c->n -= 2;
}

static inline int is_marker(const Ctx *c, int d) { return c->origin[d] < c->nv0 && c->marker[c->origin[d]]; }

/* The child: compact darts (markers removed), then loops, the bound, acceptance, the code. */
typedef struct {
    int D;                  /* darts */
    int rot[MAXD], irot[MAXD], twin[MAXD];  /* as in Ctx */
    int face[MAXD];         /* the face on a dart's left */
    int face_size[MAXD];    /* sides of each face */
    int face_dart[MAXD];    /* a dart of each face */
    int meets_once;         /* no face has two sides on one loop (set by meeting_need) */
    int loop[MAXD];         /* the loop a dart lies on */
    int nfaces, nloops;
    int loop_crossings[MAXL];  /* crossings of each loop */
    uint64_t adj[MAXL];     /* the loops each loop crosses, a bit each */
    int best[MAXD], code[MAXD], num[MAXD], order[MAXD];  /* canonical code: least so far, the
                                                            current one, and its numbering */
} Child;

static Child child;

static int face_key(const Child *h, int o, int d)
{
    /* an isomorphism invariant of (orientation, dart): mirrored, left and right swap */
    int f = o ? h->face[h->twin[d]] : h->face[d];
    return h->loop_crossings[h->loop[d]] * 64 + h->face_size[f];
}

/* The code from root r in orientation o (0: rot, 1: irot); returns -1 if it exceeds best at
 * some position, 0 if equal, 1 if smaller (and then it is in h->code).  *first gets the loop
 * of the first dart in the numbering that lies on a candidate loop. */
static int code_from(Child *h, int o, int r, int have_best, uint64_t cand, int *first)
{
    const int *rot = o ? h->irot : h->rot;
    int cnt = 0, smaller = !have_best;
    for (int d = 0; d < h->D; d++) h->num[d] = -1;
    *first = -1;
#define VISIT(t0) do { int t_ = (t0); for (int j_ = 0; j_ < 4; j_++) { h->num[t_] = cnt; \
        h->order[cnt++] = t_; t_ = rot[t_]; } } while (0)
    VISIT(r);
    for (int i = 0; i < h->D; i++) {
        int d = h->order[i], t = h->twin[d];
        if (*first < 0 && (cand >> h->loop[d] & 1)) *first = h->loop[d];
        if (h->num[t] < 0) VISIT(t);
        int v = h->num[t];
        h->code[i] = v;
        if (!smaller) {
            if (v > h->best[i]) return -1;
            if (v < h->best[i]) smaller = 1;
        }
    }
#undef VISIT
    return smaller ? 1 : 0;
}

static int connected_without(const Child *h, int skip)
{
    uint64_t all = 0, seen, frontier;
    for (int l = 0; l < h->nloops; l++) if (l != skip) all |= (uint64_t)1 << l;
    if (!all) return 1;
    int s = skip == 0 ? 1 : 0;
    seen = frontier = (uint64_t)1 << s;
    while (frontier) {
        uint64_t next = 0;
        for (int l = 0; l < h->nloops; l++) if (frontier >> l & 1) next |= h->adj[l];
        next &= all & ~seen;
        seen |= next;
        frontier = next;
    }
    return seen == all;
}

/* Faces and their sizes; returns the child's bound: crossings plus the needs of its regions. */
static int child_faces(Child *h)
{
    int total = h->D / 4;
    for (int d = 0; d < h->D; d++) h->irot[h->rot[d]] = d;
    for (int d = 0; d < h->D; d++) h->face[d] = -1;
    h->nfaces = 0;
    for (int d = 0; d < h->D; d++) {
        if (h->face[d] >= 0) continue;
        int k = 0, e = d;
        do { h->face[e] = h->nfaces; k++; e = h->irot[h->twin[e]]; } while (e != d);
        h->face_dart[h->nfaces] = d;
        h->face_size[h->nfaces++] = k;
        total += need(k);
    }
    return total;
}

/* Loops (the orbit of a dart under straight-ahead, with its reverse), their crossings and
 * which loops cross; -1 when a loop crosses itself or there are too many loops. */
static int child_loops(Child *h)
{
    for (int d = 0; d < h->D; d++) h->loop[d] = -1;
    h->nloops = 0;
    for (int d = 0; d < h->D; d++) {
        if (h->loop[d] >= 0) continue;
        if (h->nloops >= MAXL) return -1;
        int e = d;
        do { h->loop[e] = h->nloops; h->loop[h->twin[e]] = h->nloops; e = h->rot[h->rot[h->twin[e]]]; } while (e != d);
        h->loop_crossings[h->nloops] = 0;
        h->adj[h->nloops] = 0;
        h->nloops++;
    }
    for (int d = 0; d < h->D; d++) {
        int a = h->loop[d], b = h->loop[h->rot[d]];
        if (a == b) return -1;
        h->loop_crossings[a]++;
        h->adj[a] |= (uint64_t)1 << b;
    }
    for (int l = 0; l < h->nloops; l++) h->loop_crossings[l] /= 2;
    return 0;
}

/* Cut 5 of docs/catalog.md: in a genus-0 polycube no corner meets a strip twice (the loop
 * separates the sphere, so both edges would leave the corner in the same direction), and a
 * region with k sides on one loop must be cut into at least k pieces, which takes k - 1 of the
 * later crossings' shares.  Returns what this adds to cut 1's bound (the sum over regions of
 * max(0, k - 1 - need(s)), k the most sides on one loop), and sets h->meets_once. */
static int meeting_need(Child *h)
{
    static unsigned stamp[MAXL], count[MAXL], now;
    int extra = 0;
    h->meets_once = 1;
    for (int f = 0; f < h->nfaces; f++) {
        unsigned most = 0;
        int d = h->face_dart[f], e = d;
        now++;
        do {
            int l = h->loop[e];
            if (stamp[l] != now) { stamp[l] = now; count[l] = 0; }
            if (++count[l] > most) most = count[l];
            e = h->irot[h->twin[e]];
        } while (e != d);
        if (most > 1) {
            int more = (int)most - 1 - need(h->face_size[f]);
            h->meets_once = 0;
            if (more > 0) extra += more;
        }
    }
    return extra;
}

/* The least code over the roots of least invariant, into h->best; returns whether some root
 * reaching it numbers a dart of `wanted` before any other loop of `cand` (McKay's test). */
static int child_code(Child *h, uint64_t cand, int wanted)
{
    int low = 1 << 30, have = 0, accepted = 0;
    for (int o = 0; o < 2; o++)
        for (int d = 0; d < h->D; d++) { int k = face_key(h, o, d); if (k < low) low = k; }
    for (int o = 0; o < 2; o++) {
        for (int d = 0; d < h->D; d++) {
            if (face_key(h, o, d) != low) continue;
            int first, r = code_from(h, o, d, have, cand, &first);
            if (r < 0) continue;
            if (r > 0) {
                memcpy(h->best, h->code, sizeof(int) * h->D);
                have = 1;
                accepted = 0;
            }
            if (first == wanted) accepted = 1;
        }
    }
    return accepted;
}

/* A candidate map: regions of 3 to 6 sides, no region on both sides of an edge, no two
 * regions sharing two edges (the quad mesh is then simple with degrees 3 to 6). */
static int child_is_candidate(const Child *h)
{
    static unsigned char pair[MAXV * MAXV / 4];
    int nf = h->nfaces;
    for (int f = 0; f < nf; f++) if (h->face_size[f] < 3 || h->face_size[f] > 6) return 0;
    if ((size_t)nf * nf > sizeof(pair)) return -1;
    memset(pair, 0, (size_t)nf * nf);
    for (int d = 0; d < h->D; d++) {
        int a = h->face[d], b = h->face[h->twin[d]];
        if (a == b || pair[a * nf + b]) return 0;
        pair[a * nf + b] = 1;
    }
    return 1;
}

/* Cut 4 of docs/catalog.md: a polycube's axes colour the graph of crossing loops properly with
 * three colours (loops of one axis never cross), and deleting a loop keeps a colouring, so
 * every arrangement on the canonical construction path of a candidate that carries a polycube
 * is 3-colourable.  Backtracking over the loops, most crossed first, colour bits per loop. */
static int colour_from(int n, const uint64_t *adj, const int *order, int i, unsigned char *colour)
{
    if (i == n) return 1;
    int l = order[i];
    unsigned used = 0;
    for (int m = 0; m < n; m++)
        if ((adj[l] >> m & 1) && colour[m]) used |= 1u << colour[m];
    for (unsigned char k = 1; k <= 3; k++) {
        if (used >> k & 1) continue;
        colour[l] = k;
        if (colour_from(n, adj, order, i + 1, colour)) return 1;
    }
    colour[l] = 0;
    return 0;
}

/* Whether the graph on n vertices with neighbour masks adj is properly 3-colourable. */
static int colourable3(int n, const uint64_t *adj)
{
    int order[MAXL + 1], deg[MAXL + 1];
    unsigned char colour[MAXL + 1] = {0};
    for (int l = 0; l < n; l++) {
        order[l] = l;
        deg[l] = __builtin_popcountll(adj[l]);
    }
    for (int i = 1; i < n; i++)   /* most crossed first: the tightest choices early */
        for (int j = i; j > 0 && deg[order[j]] > deg[order[j - 1]]; j--) {
            int t = order[j]; order[j] = order[j - 1]; order[j - 1] = t;
        }
    return colour_from(n, adj, order, 0, colour);
}

static PyObject *code_bytes(const Child *h)
{
    uint16_t buf[MAXD];
    for (int i = 0; i < h->D; i++) buf[i] = (uint16_t)h->best[i];
    return PyBytes_FromStringAndSize((const char *)buf, (Py_ssize_t)(2 * h->D));
}

static void emit(Ctx *c, int newdart)
{
    Child *h = &child;
    int id[MAXD];
    int D = 0;
    c->closed++;
    for (int d = 0; d < c->n; d++) id[d] = is_marker(c, d) ? -1 : D++;
    h->D = D;
    for (int d = 0; d < c->n; d++) {
        if (id[d] < 0) continue;
        int t = c->twin[d];
        if (id[t] < 0) t = c->twin[c->rot[t]];      /* through the marker */
        h->twin[id[d]] = id[t];
        h->rot[id[d]] = id[c->rot[d]];             /* markers are never on a crossing */
    }
    int bound = child_faces(h);
    if (bound > c->limit) { c->bounded++; return; }
    if (child_loops(h) < 0) { c->failed = 2; return; }
    if (c->meet_cut && bound + meeting_need(h) > c->limit) { c->met_twice++; return; }
    if (c->colour_cut && !colourable3(h->nloops, h->adj)) { c->uncolourable++; return; }
    int newloop = h->loop[id[newdart]];
    /* candidates: deletable loops with the fewest crossings */
    uint64_t cand = 0;
    int fewest = 1 << 30;
    for (int l = 0; l < h->nloops; l++) {
        if (!connected_without(h, l)) continue;
        if (h->loop_crossings[l] < fewest) { fewest = h->loop_crossings[l]; cand = 0; }
        if (h->loop_crossings[l] == fewest) cand |= (uint64_t)1 << l;
    }
    if (!(cand >> newloop & 1) || !child_code(h, cand, newloop)) { c->rejected++; return; }
    int final = child_is_candidate(h);
    if (final < 0) { c->failed = 2; return; }
    if (c->meet_cut && !h->meets_once) final = 0;
    PyObject *code = code_bytes(h);
    PyObject *item = code ? Py_BuildValue("(Ni)", code, final) : NULL;
    if (!item || PyList_Append(c->out, item) < 0) c->failed = 1;
    Py_XDECREF(item);
}

/* Every face of the partial map carries a label and its number of corners on each of its darts
 * (lab, fs).  A step changes three faces only (the current one splits in two, the one across
 * the crossed edge gains a corner), so a node updates those and restores them on the way back;
 * the bound of the faces that are not open (base2) comes from the parent. */
static void label_face(Ctx *c, int d, unsigned label, int size, int need2)
{
    int e = d;
    do { c->flabel[e] = label; c->fsize[e] = size; c->fneed2[e] = need2; e = fnext(c, e); } while (e != d);
}

/* Cut 5's need of a face with s sides, at most k of them on one loop: max(need(s), k - 1). */
static inline int need5(const Ctx *c, int s, int k)
{
    return c->meet_cut && k - 1 > need(s) ? k - 1 : need(s);
}

/* The loop a dart of the partial map lies on: the parent's, or the new one (id nloops; the
 * single loop's parent has no loop numbering: its loop is 0 and the new one 1). */
static inline int dart_loop(const Ctx *c, int d)
{
    int p = c->parent_dart[d];
    if (p < 0) return c->nloops ? c->nloops : 1;
    return c->nloops ? c->loop_of[p] : 0;
}

/* The parent's faces labelled; returns twice their needs (with cut 5's, when it is on). */
static int label_all(Ctx *c)
{
    static unsigned stamp[MAXL + 2], count[MAXL + 2], now;
    int st = ++c->stamp, sum = 0;
    for (int d = 0; d < c->n; d++) {
        if (c->seen[d] == st) continue;
        int s = 0, e = d;
        unsigned most = 0;
        now++;
        do {
            c->seen[e] = st;
            if (!is_marker(c, e)) {  /* a dart from a corner starts a side */
                int l = dart_loop(c, e);
                s++;
                if (stamp[l] != now) { stamp[l] = now; count[l] = 0; }
                if (++count[l] > most) most = count[l];
            }
            e = fnext(c, e);
        } while (e != d);
        int n2 = 2 * need5(c, s, (int)most);
        label_face(c, d, ++c->next_label, s, n2);
        sum += n2;
    }
    return sum;
}

/* Cut 4 while drawing: the curve being drawn will cross at least the loops it has crossed so
 * far, so if the parent's crossing graph with a new vertex joined to those loops is not
 * 3-colourable, no way of finishing the curve gives a child that is (a path is abandoned as
 * soon as a first crossing with a loop makes it so). */
static int curve_colourable(const Ctx *c)
{
    uint64_t adj[MAXL + 1];
    int n = c->nloops;
    for (int l = 0; l < n; l++) adj[l] = c->parent_adj[l] | ((c->crossed >> l & 1) ? (uint64_t)1 << n : 0);
    adj[n] = c->crossed;
    return colourable3(n + 1, adj);
}

static void dfs(Ctx *c, int x, int y0, int cr, int base2)
{
    int face[MAXD], corner[MAXD + 1], k = 0, e = x, at = -1;
    if (c->failed) return;
    c->nodes++;
    /* the current face (left of x), with its corners counted along it */
    corner[0] = 0;
    do {
        if (e == y0) at = k;
        face[k] = e;
        corner[k + 1] = corner[k] + !is_marker(c, e);
        k++;
        e = fnext(c, e);
    } while (e != x);
    int sg = corner[k];
    unsigned lg = ++c->next_label;
    for (int i = 0; i < k; i++) { c->flabel[face[i]] = lg; c->fsize[face[i]] = sg; c->fneed2[face[i]] = 0; }
    int closable = at >= 0, sz = c->fsize[y0];
    unsigned lz = c->flabel[y0];
    /* A loop of the parent that stays deletable (the new loop meets another loop too) must
     * have at least as many crossings as the new one: the new loop meets the other loops at
     * most as often as that loop's crossings in the parent. */
    int crossed = 0;
    for (int l = 0; l < c->nloops; l++) crossed += c->crossings_with[l] > 0;
    for (int l = 0; l < c->nloops; l++)
        if (c->deletable[l] && crossed > (c->crossings_with[l] > 0) && cr - c->crossings_with[l] > c->loop_crossings[l]) return;
    /* Twice a lower bound on the child's crossings and on those of later loops: base2 covers
     * the faces other than the open ones (regions of the child, or pieces later loops must
     * cut to size); the open faces will hold the rest of the path. */
    int limit2 = 2 * c->limit;
    if (base2 + (closable ? both2(sg) : half2(sg) + half2(sz)) > limit2) return;
    /* Closing cuts the current face into the darts before y0 and those from y0 on, each with
     * the chord: the child's exact bound, before building it. */
    if (cr >= 2 && closable) {
        int a = corner[at] + 1, b = corner[k] - corner[at] + 1;
        if (base2 + 2 * need(a) + 2 * need(b) <= limit2) {
            chord(c, x, y0);
            emit(c, c->n - 2);
            unchord(c, x, y0);
        } else {
            c->closed++;
            c->bounded++;
        }
    }
    if (cr >= c->budget || c->n + 4 > MAXD) return;
    /* Cut 5 for the two pieces a chord to a new point on face[i] makes: most sides on one loop
     * in face[0..i] and the chord (m1), and in the rest of face[i] (from the new point),
     * face[i+1..k-1] and the chord (m2); a dart from a marker continues a side. */
    static unsigned stamp[MAXL + 2], count[MAXL + 2], now;
    int m1[MAXD], m2[MAXD], newl = c->nloops ? c->nloops : 1;
    if (c->meet_cut) {
        unsigned most = 1;
        now++;
        stamp[newl] = now; count[newl] = 1;
        for (int i = 0; i < k; i++) {
            if (!is_marker(c, face[i])) {
                int l = dart_loop(c, face[i]);
                if (stamp[l] != now) { stamp[l] = now; count[l] = 0; }
                if (++count[l] > most) most = count[l];
            }
            m1[i] = (int)most;
        }
        most = 1;
        now++;
        stamp[newl] = now; count[newl] = 1;
        for (int i = k - 1; i >= 0; i--) {
            int l = dart_loop(c, face[i]);
            if (stamp[l] != now) { stamp[l] = now; count[l] = 0; }
            m2[i] = (int)(count[l] + 1 > most ? count[l] + 1 : most);
            if (!is_marker(c, face[i]) && ++count[l] > most) most = count[l];
        }
    }
    /* The chord to a new point on an edge d of the current face cuts it in two and enters the
     * face across d: the child's bound, before drawing it. */
    int go[MAXD], gob[MAXD], goi[MAXD], gn1[MAXD], gn2[MAXD], ngo = 0;
    for (int i = 0; i < k; i++) {
        int d = face[i];
        if (c->on_curve[d] || c->parent_edge[c->parent_dart[d]] < c->first_edge || d == c->near || d == c->near_twin) continue;
        int t = c->twin[d], z = c->flabel[t] == lz;   /* is the face across the closing face? */
        int s1 = corner[i + 1] + 1, s2 = corner[k] - corner[i + 1] + 2, sh = c->fsize[t];
        int nb2 = base2 + 2 - (z ? 0 : c->fneed2[t]), next2;
        int n1 = 2 * need5(c, s1, c->meet_cut ? m1[i] : 0), n2 = 2 * need5(c, s2, c->meet_cut ? m2[i] : 0);
        if (closable) {   /* the piece with the closing angle stays open */
            int keep = at <= i ? s1 : s2;
            if (at <= i) n1 = 0; else n2 = 0;
            nb2 += n1 + n2;
            next2 = nb2 + half2(keep) + half2(sh + 1);
        } else {
            nb2 += n1 + n2;
            next2 = nb2 + (z ? both2(sz + 1) : half2(sh + 1) + half2(sz));
        }
        if (next2 <= limit2) { go[ngo] = d; gob[ngo] = nb2; goi[ngo] = i; gn1[ngo] = n1; gn2[ngo++] = n2; }
    }
    for (int j = 0; j < ngo; j++) {
        int d = go[j], i = goi[j], e1, e2, l = c->nloops ? c->loop_of[c->parent_dart[d]] : 0;
        int t = c->twin[d], sh = c->fsize[t], nh = c->fneed2[t];
        unsigned lh = c->flabel[t];
        subdivide(c, d, &e1, &e2);
        chord(c, x, e2);
        /* the two pieces: face[0..i] with the chord's dart at q, and e2, face[i+1..] with
         * the chord's dart at p */
        unsigned l1 = ++c->next_label, l2 = ++c->next_label;
        int s1 = corner[i + 1] + 1, s2 = corner[k] - corner[i + 1] + 2;
        int a = c->n - 2, b = c->n - 1;
        int n1 = gn1[j], n2 = gn2[j];   /* what the bound counts for each piece (0: open) */
        for (int m = 0; m <= i; m++) { c->flabel[face[m]] = l1; c->fsize[face[m]] = s1; c->fneed2[face[m]] = n1; }
        c->flabel[b] = l1; c->fsize[b] = s1; c->fneed2[b] = n1;
        for (int m = i + 1; m < k; m++) { c->flabel[face[m]] = l2; c->fsize[face[m]] = s2; c->fneed2[face[m]] = n2; }
        c->flabel[e2] = l2; c->fsize[e2] = s2; c->fneed2[e2] = n2;
        c->flabel[a] = l2; c->fsize[a] = s2; c->fneed2[a] = n2;
        uint64_t before = c->crossed;
        if (c->nloops && !c->crossings_with[l]++) {
            c->crossed |= (uint64_t)1 << l;
            if (c->colour_cut && !curve_colourable(c)) { c->uncolourable++; goto undo; }
        }
        dfs(c, e1, y0, cr + 1, gob[j]);
    undo:
        if (c->nloops) c->crossings_with[l]--;
        c->crossed = before;
        unchord(c, x, e2);
        unsubdivide(c, d, e1);
        for (int m = 0; m < k; m++) { c->flabel[face[m]] = lg; c->fsize[face[m]] = sg; c->fneed2[face[m]] = 0; }
        label_face(c, t, lh, sh, nh);
    }
}

static Ctx ctx;

/* Numbers the darts from root r in orientation o (rot, or irot when o is 1) breadth first,
 * four a crossing, and writes each dart's twin's number into code; stops early and returns
 * 1 if that code differs from ref (when ref is given). */
static int number_from(const int *rot, const int *twin, int D, int r, int *num, int *order,
                       int *code, const int *ref)
{
    int cnt = 0;
    for (int d = 0; d < D; d++) num[d] = -1;
    for (int t = r, j = 0; j < 4; j++) { num[t] = cnt; order[cnt++] = t; t = rot[t]; }
    for (int i = 0; i < D; i++) {
        int t = twin[order[i]];
        if (num[t] < 0)
            for (int j = 0; j < 4; j++) { num[t] = cnt; order[cnt++] = t; t = rot[t]; }
        code[i] = num[twin[order[i]]];
        if (ref && code[i] != ref[i]) return 1;
    }
    return 0;
}

/* Marks the edges (by their lesser dart) that are the least of their orbit under the parent's
 * automorphisms, mirror images included: a curve's images under them give isomorphic children,
 * and every orbit of curves has a member whose least crossed edge is such an edge. */
static void edge_orbit_minima(Ctx *c, unsigned char *is_min)
{
    static int num0[MAXD], order0[MAXD], ref[MAXD], num[MAXD], order[MAXD], code[MAXD];
    int D = c->n;
    Child *h = &child;   /* for the invariant that automorphisms keep: roots are tried by it */
    h->D = D;
    memcpy(h->rot, c->rot, sizeof(int) * (size_t)D);
    memcpy(h->twin, c->twin, sizeof(int) * (size_t)D);
    child_faces(h);
    child_loops(h);
    int low = 1 << 30, root = 0;
    for (int d = 0; d < D; d++) { int k = face_key(h, 0, d); if (k < low) { low = k; root = d; } }
    for (int d = 0; d < D; d++) is_min[d] = d < c->twin[d];
    number_from(c->rot, c->twin, D, root, num0, order0, ref, NULL);
    for (int o = 0; o < 2; o++) {
        const int *rot = o ? c->irot : c->rot;
        for (int r = 0; r < D; r++) {
            if (face_key(h, o, r) != low || number_from(rot, c->twin, D, r, num, order, code, ref)) continue;
            for (int d = 0; d < D; d++) {    /* d -> order[num0[d]] is an automorphism */
                int img = order[num0[d]];
                if (is_min[d] && c->parent_edge[img] < d) is_min[d] = 0;
            }
        }
    }
}

/* The parent's loops, their crossings, and which ones leave it connected when deleted. */
static int parent_loops(Ctx *c)
{
    uint64_t adj[MAXL];
    int n = c->n;
    for (int d = 0; d < n; d++) c->loop_of[d] = -1;
    c->nloops = 0;
    for (int d = 0; d < n; d++) {
        if (c->loop_of[d] >= 0) continue;
        if (c->nloops >= MAXL) return -1;
        int e = d;
        do { c->loop_of[e] = c->nloops; c->loop_of[c->twin[e]] = c->nloops; e = c->rot[c->rot[c->twin[e]]]; } while (e != d);
        c->loop_crossings[c->nloops] = 0;
        adj[c->nloops++] = 0;
    }
    for (int d = 0; d < n; d++) {
        c->loop_crossings[c->loop_of[d]]++;
        adj[c->loop_of[d]] |= (uint64_t)1 << c->loop_of[c->rot[d]];
    }
    memcpy(c->parent_adj, adj, sizeof(uint64_t) * (size_t)c->nloops);
    for (int l = 0; l < c->nloops; l++) {
        c->loop_crossings[l] /= 2;
        uint64_t all = 0, seen, frontier;
        for (int m = 0; m < c->nloops; m++) if (m != l) all |= (uint64_t)1 << m;
        seen = frontier = all & -all;
        while (frontier) {
            uint64_t next = 0;
            for (int m = 0; m < c->nloops; m++) if (frontier >> m & 1) next |= adj[m];
            next &= all & ~seen;
            seen |= next;
            frontier = next;
        }
        c->deletable[l] = seen == all;
    }
    return 0;
}

static PyObject *children(PyObject *self, PyObject *args)
{
    Py_buffer rb, tb;
    int limit, colour_cut = 1, meet_cut = 1;
    if (!PyArg_ParseTuple(args, "y*y*i|pp", &rb, &tb, &limit, &colour_cut, &meet_cut)) return NULL;
    if (limit < 0 || limit > MAXD / 4) {  /* the arrays hold MAXD darts: four a crossing */
        PyBuffer_Release(&rb); PyBuffer_Release(&tb);
        return PyErr_Format(PyExc_ValueError, "a limit of %d crossings: the compiled search holds 0 to %d",
                            limit, MAXD / 4);
    }
    Ctx *c = &ctx;
    int n = (int)(tb.len / 2), implicit = rb.len == 0;
    static uint16_t blocks[MAXD];   /* an empty rot: four darts a crossing, in order */
    if (implicit)
        for (int d = 0; d < n && d < MAXD; d++) blocks[d] = (uint16_t)(4 * (d / 4) + (d + 1) % 4);
    const uint16_t *rot = implicit ? blocks : rb.buf, *twin = tb.buf;
    int bad = (!implicit && rb.len != tb.len) || tb.len % 2 || n < 2 || n > MAXD / 2 || (implicit && n % 4);
    static unsigned char hit[MAXD];
    if (!bad) {
        memset(hit, 0, (size_t)n);
        for (int d = 0; d < n && !bad; d++)   /* rot a permutation, twin an involution without fixed points */
            bad = rot[d] >= n || twin[d] >= n || hit[rot[d]]++ || twin[twin[d]] != d || twin[d] == d;
    }
    if (bad) {
        PyBuffer_Release(&rb); PyBuffer_Release(&tb);
        return PyErr_Format(PyExc_ValueError, "not an arrangement's rot and twin arrays");
    }
    memset(c, 0, sizeof(*c));
    c->colour_cut = colour_cut;
    c->meet_cut = meet_cut;
    c->n = n;
    for (int d = 0; d < n; d++) {
        c->rot[d] = rot[d]; c->twin[d] = twin[d]; c->parent_dart[d] = d; c->origin[d] = -1;
        c->parent_edge[d] = d < twin[d] ? d : twin[d];
    }
    PyBuffer_Release(&rb); PyBuffer_Release(&tb);
    for (int d = 0; d < n; d++) c->irot[c->rot[d]] = d;
    for (int d = 0; d < n; d++) {
        if (c->origin[d] >= 0) continue;
        int e = d, deg = 0;
        do { c->origin[e] = c->nv; deg++; e = c->rot[e]; } while (e != d);
        if (deg != 4 && deg != 2) return PyErr_Format(PyExc_ValueError, "a vertex of degree %d", deg);
        c->marker[c->nv++] = deg == 2;
    }
    c->nv0 = c->nv;
    int markers = 0;
    for (int v = 0; v < c->nv; v++) markers += c->marker[v];
    c->parent_crossings = c->nv - markers;
    c->limit = limit;
    c->budget = limit - c->parent_crossings;
    if (!markers && parent_loops(c) < 0) return PyErr_Format(PyExc_ValueError, "more than %d loops", MAXL);
    static unsigned char is_min[MAXD];
    if (markers) for (int d = 0; d < n; d++) is_min[d] = d < c->twin[d];
    else edge_orbit_minima(c, is_min);
    c->out = PyList_New(0);
    if (!c->out) return NULL;
    int needs2 = label_all(c);
    for (int e = 0; e < n && !c->failed; e++) {
        if (!is_min[e]) continue;
        int e1, e2, l = c->nloops ? c->loop_of[e] : 0, te = c->twin[e];
        int sa = c->fsize[e], sb = c->fsize[te], na = c->fneed2[e], nb = c->fneed2[te];
        unsigned la = c->flabel[e], lb = c->flabel[te];
        c->first_edge = e;
        subdivide(c, e, &e1, &e2);
        /* the faces on either side of e gain the start as a corner; they are the open ones */
        label_face(c, e, la, sa + 1, 0);
        label_face(c, e1, lb, sb + 1, 0);
        int base2 = 2 * (c->parent_crossings + 1) + needs2 - na - nb;
        /* the start is the new loop's crossing on e nearest to e's origin */
        c->near = e;
        c->near_twin = e1;
        c->crossings_with[l]++;
        c->crossed = c->nloops ? (uint64_t)1 << l : 0;
        dfs(c, e1, e2, 1, base2);
        c->crossings_with[l]--;
        unsubdivide(c, e, e1);
        label_face(c, e, la, sa, na);
        label_face(c, te, lb, sb, nb);
    }
    if (c->failed) {
        Py_DECREF(c->out);
        if (c->failed == 2) return PyErr_Format(PyExc_ValueError, "more than %d loops", MAXL);
        return NULL;
    }
    PyObject *res = Py_BuildValue("(N(LLLLLL))", c->out, c->nodes, c->closed, c->bounded, c->rejected,
                                  c->uncolourable, c->met_twice);
    return res;
}

static PyObject *canonical(PyObject *self, PyObject *args)
{
    Py_buffer rb, tb;
    int meet_cut = 1;
    if (!PyArg_ParseTuple(args, "y*y*|p", &rb, &tb, &meet_cut)) return NULL;
    Child *h = &child;
    int n = (int)(rb.len / 2), bad = rb.len != tb.len || rb.len % 2 || n < 4 || n % 4 || n > MAXD;
    const uint16_t *rot = rb.buf, *twin = tb.buf;
    static int seen[MAXD];
    if (!bad) {
        memset(seen, 0, sizeof(int) * (size_t)n);
        for (int d = 0; d < n && !bad; d++) {
            bad = rot[d] >= n || twin[d] >= n || twin[d] == d || twin[twin[d]] != d || seen[rot[d]]++;
            h->rot[d] = rot[d];
            h->twin[d] = twin[d];
        }
    }
    PyBuffer_Release(&rb);
    PyBuffer_Release(&tb);
    if (bad) return PyErr_Format(PyExc_ValueError, "not the rot and twin arrays of a 4-regular map");
    h->D = n;
    /* every crossing has four darts, and the map is connected */
    for (int d = 0; d < n; d++) {
        int e = d, k = 0;
        do { e = h->rot[e]; k++; } while (e != d && k <= 4);
        if (k != 4) return PyErr_Format(PyExc_ValueError, "a crossing without four darts");
    }
    int stack[MAXD], top = 0, reached = 1;
    memset(seen, 0, sizeof(int) * (size_t)n);
    seen[0] = 1;
    stack[top++] = 0;
    while (top) {
        int d = stack[--top], nb[2] = {h->rot[d], h->twin[d]};
        for (int j = 0; j < 2; j++)
            if (!seen[nb[j]]) { seen[nb[j]] = 1; reached++; stack[top++] = nb[j]; }
    }
    if (reached != n) return PyErr_Format(PyExc_ValueError, "the map is not connected");
    child_faces(h);
    if (child_loops(h) < 0) return PyErr_Format(PyExc_ValueError, "a loop crosses itself (or more than %d loops)", MAXL);
    child_code(h, 0, -1);
    meeting_need(h);
    int final = child_is_candidate(h) > 0 && (!meet_cut || h->meets_once);
    return Py_BuildValue("(Ni)", code_bytes(h), final);
}

static PyMethodDef methods[] = {
    {"canonical", canonical, METH_VARARGS,
     "canonical(rot, twin, meet_cut=True) -> (canonical twin array, is_candidate) of an\n"
     "arrangement; with meet_cut a candidate also has no region with two sides on one loop"},
    {"children", children, METH_VARARGS,
     "children(rot, twin, limit, colour_cut=True, meet_cut=True) -> (children, (curves drawn,\n"
     "closed, over the bound, not canonical, not 3-colourable, over cut 5's bound)): the children of an arrangement (rot and twin as\n"
     "uint16 arrays; an empty rot means the rot of a canonical arrangement, four darts a\n"
     "crossing), each as (canonical twin array, is_candidate), with at most limit crossings\n"
     "after every cut; colour_cut applies cut 4 (crossing graphs must be 3-colourable), meet_cut\n"
     "cut 5 (a region must end with at most one side on each loop)"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_arrangements", NULL, -1, methods};

PyMODINIT_FUNC PyInit__arrangements(void) { return PyModule_Create(&module); }
