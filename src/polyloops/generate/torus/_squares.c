/* The two-axis arrangements B listed directly, as square-tiled surfaces (the compiled first
 * stage of polyloops/generate/torus/squares.py, which proves what this lists; its Python twin
 * there follows the same steps).
 *
 * A B with n crossings is a 4-regular map whose edges join darts of one parity: darts 4v+0 and
 * 4v+2 lie on v's loop of the first class, 4v+1 and 4v+3 on its loop of the second (darts
 * numbered counter-clockwise round each crossing).  Each crossing is a square of the surface
 * tiled by the dual squares, and each dart a side of its square.
 *
 * Every B is met once for each of its 8n roots (a square, one of its four darts as dart 0, and
 * one of the two orientations), labelled from the root breadth first: squares numbered in the
 * order they are first reached, each square's darts numbered from the one it was reached by,
 * that dart getting the number of the reaching dart plus two (mod 4).  The labelled map's twin
 * array is its code from that root.  The search writes the code position by position: the
 * dart at the next position is either joined to a new square (the next number, at the dart
 * number the rule gives) or to a free dart of the same parity further on.  A leaf is kept when
 * no other root gives a smaller code (McKay's canonical labelling by breadth-first search; the
 * leaf is kept exactly once for each B up to homeomorphism, the mirror and the swap of the
 * classes included).
 *
 * A branch ends when the partial surface (the squares glued along the darts joined so far, a
 * connected surface with boundary) has a genus above the target: a connected subsurface of a
 * closed surface of genus g has genus at most g.  Its Euler characteristic is C + m - A/2 (C
 * closed vertices, m squares, A joined darts) and its boundary components are the cycles of
 * the boundary walk, so genus h = (2 - b - chi) / 2.  A branch also ends when the squares left
 * cannot close enough vertices for the target genus.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdint.h>
#include <string.h>

#define MAXN 24
#define MAXD (4 * MAXN)

typedef struct {
    int n, genus, faces;      /* crossings, the target genus, its vertex count n + 2 - 2 genus */
    int tw[MAXD];             /* the twin of each dart, -1 while free */
    int m;                    /* squares created */
    int joined;               /* darts joined */
    /* Vertices as paths of corners: corner d is followed by rot(tw(d)) once tw(d) is known; an
     * open path's ends point at each other (oe) and know its length (len). */
    int oe[MAXD], len[MAXD];
    int closed;               /* closed vertices (cycles of corners) */
    int closed_corners;
    /* Zones, as unions of corners (corner c of a square lies between its darts c and c + 1):
     * uf[0] joins the ends of the sides the second class's loops cross (the first class's
     * zones), uf[1] those the first class's cross; a dart's side has its ends at the corners
     * before and at it.  Union by size, no compression, undone from the history. */
    int up[2][MAXD], size[2][MAXD];
    int hist[8 * MAXD], nhist;
    /* the search */
    int split, res, mod;      /* the share: subtrees at `split` joined darts, res of every mod */
    long long split_seen;
    long long nodes, leaves, not_canonical, lower_genus;
    PyObject *out;            /* the kept arrangements, or NULL to count them only */
    long long kept;
    int failed;
} S;

static inline int rot(int d) { return (d & ~3) | ((d + 1) & 3); }
static inline int irot(int d) { return (d & ~3) | ((d + 3) & 3); }

typedef struct { int a, b, oa, ob, la, lb, closed; } Undo;

/* corner `a` (a path's last corner) now continues with corner `b` (a path's first) */
static void link_corners(S *s, int a, int b, Undo *u) {
    u->closed = 0;
    if (s->oe[a] == b) {  /* the path closes: a vertex */
        s->closed++;
        s->closed_corners += s->len[a];
        u->closed = 1;
        u->a = a;
        return;
    }
    int h = s->oe[a], t = s->oe[b];
    u->a = h; u->b = t;
    u->oa = s->oe[h]; u->ob = s->oe[t];
    u->la = s->len[h]; u->lb = s->len[t];
    int total = s->len[a] + s->len[b];
    s->oe[h] = t; s->oe[t] = h;
    s->len[h] = total; s->len[t] = total;
}

static void unlink_corners(S *s, int a, Undo *u) {
    if (u->closed) {
        s->closed--;
        s->closed_corners -= s->len[a];
        return;
    }
    s->oe[u->b] = u->ob; s->len[u->b] = u->lb;
    s->oe[u->a] = u->oa; s->len[u->a] = u->la;
}

static int uf_find(const S *s, int k, int x) {
    while (s->up[k][x] != x) x = s->up[k][x];
    return x;
}

static void uf_union(S *s, int k, int a, int b) {
    a = uf_find(s, k, a); b = uf_find(s, k, b);
    if (a == b) return;
    if (s->size[k][a] < s->size[k][b]) { int t = a; a = b; b = t; }
    s->up[k][b] = a;
    s->size[k][a] += s->size[k][b];
    s->hist[s->nhist++] = k * MAXD + b;
}

static void uf_undo(S *s, int to) {
    while (s->nhist > to) {
        int h = s->hist[--s->nhist], k = h / MAXD, b = h % MAXD, a = s->up[k][b];
        s->size[k][a] -= s->size[k][b];
        s->up[k][b] = b;
    }
}

/* Whether some loop has the same zone on both sides: for the first class, the ends of a
 * square's side crossed by dart 0 (corners 3 and 0); for the second, of dart 1's (0 and 1). */
static int one_zone(const S *s) {
    for (int v = 0; v < s->m; v++) {
        if (uf_find(s, 0, 4 * v + 3) == uf_find(s, 0, 4 * v)) return 1;
        if (uf_find(s, 1, 4 * v) == uf_find(s, 1, 4 * v + 1)) return 1;
    }
    return 0;
}

static void join(S *s, int d, int e, Undo u[2]) {
    s->tw[d] = e; s->tw[e] = d;
    s->joined += 2;
    link_corners(s, d, rot(e), &u[0]);
    link_corners(s, e, rot(d), &u[1]);
    /* the glued sides' ends: corner d with corner irot(e), corner irot(d) with corner e */
    for (int k = 0; k < 2; k++) {
        uf_union(s, k, d, irot(e));
        uf_union(s, k, irot(d), e);
    }
}

static void unjoin(S *s, int d, int e, Undo u[2]) {
    unlink_corners(s, e, &u[1]);
    unlink_corners(s, d, &u[0]);
    s->tw[d] = -1; s->tw[e] = -1;
    s->joined -= 2;
}

static void add_square(S *s) {
    int base = 4 * s->m;
    for (int j = 0; j < 4; j++) {
        s->tw[base + j] = -1;
        s->oe[base + j] = base + j;
        s->len[base + j] = 1;
        for (int k = 0; k < 2; k++) { s->up[k][base + j] = base + j; s->size[k][base + j] = 1; }
    }
    s->m++;
    /* the sides the second class crosses (darts 1, 3) join corners 0-1 and 2-3 in the first
     * class's zones; those the first crosses (darts 0, 2), corners 3-0 and 1-2 in the second's */
    uf_union(s, 0, base, base + 1); uf_union(s, 0, base + 2, base + 3);
    uf_union(s, 1, base + 3, base); uf_union(s, 1, base + 1, base + 2);
}

/* Whether the partial surface may still lie in a closed surface of the target genus with n
 * squares. */
static int hopeful(S *s) {
    int m = s->m, free_ = 4 * m - s->joined;
    /* boundary components: the cycles of the walk from a free dart x to the end of the path
     * of corners that starts at rot(x) */
    int b = 0;
    if (free_) {
        static __thread unsigned char seen[MAXD];
        memset(seen, 0, 4 * m);
        for (int x = 0; x < 4 * m; x++) {
            if (s->tw[x] >= 0 || seen[x]) continue;
            b++;
            int y = x;
            while (!seen[y]) { seen[y] = 1; y = s->oe[rot(y)]; }
        }
    }
    int chi2 = 2 * (s->closed + m) - s->joined;  /* twice the Euler characteristic */
    /* genus h: 2 - 2h - b = chi */
    if (4 - 2 * b - chi2 > 4 * s->genus) return 0;
    /* vertices: the closed ones, and at most one for every two corners not yet in one */
    int open_corners = 4 * s->n - s->closed_corners;
    if (s->closed + open_corners / 2 < s->faces) return 0;
    return 1;
}

/* The code of the map from root square r, dart offset o, orientation f (f = 1: clockwise),
 * compared with the map's own labelling over its first `limit` positions: <0 when smaller, >0
 * when larger, 0 when equal or when a dart not yet joined is reached first. */
static int compare_root(const S *s, int r, int o, int f, int limit) {
    int lab[MAXN], sq[MAXN], fr[MAXN];
    for (int v = 0; v < s->m; v++) lab[v] = -1;
    lab[r] = 0; sq[0] = r; fr[r] = o;
    int next = 1;
    for (int p = 0; p < limit; p++) {
        int L = p >> 2, j = p & 3, v = sq[L];
        int x = 4 * v + ((f ? fr[v] - j : fr[v] + j) & 3);
        int y = s->tw[x];
        if (y < 0) return 0;
        int u = y >> 2, k = y & 3;
        if (lab[u] < 0) {
            lab[u] = next;
            sq[next++] = u;
            int want = (j + 2) & 3;  /* y's number in u's new frame */
            fr[u] = f ? (k + want) & 3 : (k - want) & 3;
        }
        int jj = f ? (fr[u] - k) & 3 : (k - fr[u]) & 3;
        int code = 4 * lab[u] + jj, mine = s->tw[p];
        if (code != mine) return code < mine ? -1 : 1;
    }
    return 0;
}

/* Whether no root gives a code smaller than the map's own over its first `limit` positions
 * (all joined): a smaller prefix stays smaller whatever the rest, so the branch ends. */
static int canonical_so_far(const S *s, int limit) {
    for (int r = 0; r < s->m; r++)
        for (int o = 0; o < 4; o++)
            for (int f = 0; f < 2; f++) {
                if (!r && !o && !f) continue;
                if (compare_root(s, r, o, f, limit) < 0) return 0;
            }
    return 1;
}

static void leaf(S *s) {
    s->leaves++;
    if (s->closed != s->faces) { s->lower_genus++; return; }
    if (!canonical_so_far(s, 4 * s->n)) { s->not_canonical++; return; }
    s->kept++;
    if (!s->out) return;
    uint16_t raw[MAXD];
    for (int d = 0; d < 4 * s->n; d++) raw[d] = (uint16_t)s->tw[d];
    PyObject *b = PyBytes_FromStringAndSize((const char *)raw, 8 * s->n);
    if (!b || PyList_Append(s->out, b) < 0) s->failed = 1;
    Py_XDECREF(b);
}

static void search(S *s, int d) {
    if (s->failed) return;
    /* a listing of minutes answers Ctrl-C: the KeyboardInterrupt is raised on return */
    if ((++s->nodes & 0xFFFFF) == 0 && PyErr_CheckSignals() < 0) { s->failed = 1; return; }
    while (d < 4 * s->m && s->tw[d] >= 0) d++;
    if (d == 4 * s->m) {  /* every dart of every square joined: closed */
        if (s->m == s->n) leaf(s);
        return;
    }
    if ((d & 3) == 0 && d && !canonical_so_far(s, d)) { s->not_canonical++; return; }
    if (s->joined == s->split) {
        if (s->split_seen++ % s->mod != s->res) return;
    }
    Undo u[2];
    int h0 = s->nhist;
    if (s->m < s->n) {  /* a new square, reached through its dart (d + 2) mod 4 */
        int e = 4 * s->m + ((d + 2) & 3);
        add_square(s);
        join(s, d, e, u);
        if (!one_zone(s) && hopeful(s)) search(s, d + 1);
        unjoin(s, d, e, u);
        uf_undo(s, h0);
        s->m--;
    }
    for (int e = d + 1; e < 4 * s->m; e++) {
        if (s->tw[e] >= 0 || ((e ^ d) & 1)) continue;
        join(s, d, e, u);
        if (!one_zone(s) && hopeful(s)) search(s, d + 1);
        unjoin(s, d, e, u);
        uf_undo(s, h0);
    }
}

static PyObject *bases(PyObject *self, PyObject *args) {
    int n, genus, res = 0, mod = 1, split = -1, keep = 1;
    if (!PyArg_ParseTuple(args, "ii|iiip", &n, &genus, &res, &mod, &split, &keep)) return NULL;
    if (n < 1 || n > MAXN || genus < 0 || mod < 1 || res < 0 || res >= mod) {
        PyErr_SetString(PyExc_ValueError, "crossings 1..24, genus >= 0, 0 <= res < mod");
        return NULL;
    }
    S *s = calloc(1, sizeof(S));
    if (!s) return PyErr_NoMemory();
    s->n = n; s->genus = genus; s->faces = n + 2 - 2 * genus;
    s->res = res; s->mod = mod;
    /* every branch to a B passes an open node with 2 split darts joined when split < 2n */
    if (split < 0) split = n;
    if (split > 2 * n - 1) split = 2 * n - 1;
    s->split = mod > 1 ? 2 * split : -1;
    if (keep && !(s->out = PyList_New(0))) { free(s); return NULL; }
    if (s->faces >= 1) {
        add_square(s);
        search(s, 0);
    }
    PyObject *out = s->out ? s->out : PyLong_FromLongLong(s->kept);
    if (s->failed) { Py_XDECREF(out); free(s); return NULL; }
    PyObject *r = Py_BuildValue("N(LLLLL)", out, s->nodes, s->leaves, s->lower_genus, s->not_canonical,
                                s->split_seen);
    free(s);
    return r;
}

static PyMethodDef methods[] = {
    {"bases", bases, METH_VARARGS,
     "bases(crossings, genus, res=0, mod=1, split=-1, keep=True) -> (twins, (nodes, leaves, lower genus,\n"
     "not canonical, subtrees)): every two-axis arrangement B of that genus with that many crossings, each\n"
     "once (its twin array as uint16 bytes; their number when not keep); with mod > 1, the share res of\n"
     "the subtrees met with `split` edges joined (as many as the crossings unless given)"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_squares", NULL, -1, methods};

PyMODINIT_FUNC PyInit__squares(void) { return PyModule_Create(&module); }
