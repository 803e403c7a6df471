/* The second stage of the torus search region by region (the compiled twin of
 * polyloops/generate/torus/regions.py: the same walks, cuts and order).
 *
 * The regions of B are chosen one at a time, in an order fixed by the caller.  A region's
 * chords are parallel; they are walked from one cap (two chord ends on different sides) with
 * the next chord's ends moving one forwards and one backwards round the region, and the walk
 * closes with the other cap.  Each piece between chords is a corner: 3 to 6 sides, at most two
 * of each axis of B, no two on one loop, and two sides of one axis give a parity constraint
 * between their loops' signs (Condition 3).  A branch ends when the constraints contradict each
 * other, force a cycle of a level graph of B one way round, or the points exceed the budget.
 *
 * The caller passes one int32 array:
 *   R E NL least budget
 *   E x (axis loop)                                                 of each edge
 *   R x (f ns need a0 a1  ns x (edge reverse loop axis forward))   regions in search order
 *   ncycles  ncycles x (len  len x (loop rho))
 * and gets back the complete third axes whose loops cross each region once: bytes with the
 * points of each edge, then per region in search order f, k and k chords of six bytes
 * (edge, index, reverse) x 2.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <string.h>

#define MAXR 48
#define MAXS 48
#define MAXE 96
#define MAXL 64
#define MAXK 64
#define MAXP 256

typedef struct {  /* one side of a region: a piece of an edge of B */
    int edge;   /* the edge (numbered 0..E-1 among the edges the regions use) */
    int rev;    /* 1 when the region walks the edge against its direction: points count back */
    int loop;   /* the loop of B the edge lies on */
    int axis;   /* 0 or 1: that loop's class in B's bipartition */
    int fwd;    /* +1 when the edge runs along its loop's reference walk, -1 against it */
    int first;  /* 1 on the first of the region's sides on this edge (an edge may bound it twice) */
    int other;  /* the region's other side on the same edge, or -1 */
} Side;

typedef struct {  /* a region of B (a face of the two-axis arrangement) */
    int f;          /* its face in the caller's numbering */
    int ns;         /* sides */
    int need;       /* the third-axis points it needs at least, for its pieces to be corners */
    int as[2];      /* its sides of each axis of B */
    Side s[MAXS];   /* the sides in order round the region */
} Region;

typedef struct {  /* a region's walk in progress: its chords laid from one cap to the other */
    int fixed[MAXS];    /* per side: its edge's points when already numbered, -1 when free */
    int count[MAXS];    /* per side: the chord ends placed on it so far */
    int L[MAXK];        /* per chord: the side of its end on the walk's left */
    int Rr[MAXK];       /* per chord: the side of its end on the walk's right */
    int kk;             /* chords placed */
    int cap[2];         /* per axis of B: the points the budget still allows on free edges */
    int placed[2];      /* per axis of B: the points numbered before this region */
} Walk;

#define MAXCYC 32   /* the cycles of the level graphs of B: one an axis on the torus, more at genus 2 or more */

typedef struct {  /* the whole search: B's regions in search order and the state of the walk */
    int R;          /* regions */
    int E;          /* edges of B the regions use */
    int NL;         /* loops of B */
    int least;      /* B's crossings: the least each axis's third-axis crossings count for in the bound */
    int budget;     /* the crossings the third axis may add */
    int ncyc;       /* cycles of B's level graphs to keep from being forced one way (0 to MAXCYC) */
    int edge_axis[MAXE], edge_loop[MAXE];  /* per edge: its axis of B and its loop */
    Region reg[MAXR];                       /* the regions, in search order */
    int cyclen[MAXCYC], cycloop[MAXCYC][MAXL], cycrho[MAXCYC][MAXL];  /* per cycle: its loops and senses */
    int points[MAXE];                       /* per edge: its third-axis points, -1 while free */
    int parent[MAXL], par[MAXL];            /* the parity union-find of loop signs (Condition 3) */
    int trail[MAXL], ntrail;                /* its unions, to roll back on the way up */
    int k[MAXR];                            /* per region: the chords of its chosen option */
    unsigned char ends[MAXR][MAXK][6];      /* per region and chord: (edge, index, reverse) x 2 */
    Walk w[MAXR];                           /* per region: its walk */
    long long nodes, over, incons, oneway, complete, kept;  /* counts returned to the caller:
        region options, branches over the budget, inconsistent signs, cycles forced one way,
        complete third axes, and those kept (each of their loops crossing each region once) */
    PyObject *out;  /* the list of third axes found */
    int failed;     /* 1: a Python error is set; 2: a third axis with too many points */
} Search;

static int find(Search *S, int x, int *sign) {
    int s = 1;
    while (S->parent[x] != x) { s *= S->par[x]; x = S->parent[x]; }
    *sign = s;
    return x;
}

static int relate(Search *S, int a, int b, int p) {
    int sa, sb, ra = find(S, a, &sa), rb = find(S, b, &sb);
    if (ra == rb) return sa * sb == p;
    S->parent[ra] = rb;
    S->par[ra] = sa * sb * p;
    S->trail[S->ntrail++] = ra;
    return 1;
}

static void rollback(Search *S, int mark) {
    while (S->ntrail > mark) {
        int x = S->trail[--S->ntrail];
        S->parent[x] = x;
        S->par[x] = 1;
    }
}

static int one_way(Search *S) {
    for (int c = 0; c < S->ncyc; c++) {
        int root = -1, first = 0, forced = 1;
        for (int q = 0; q < S->cyclen[c] && forced; q++) {
            int s, r = find(S, S->cycloop[c][q], &s);
            if (root < 0) { root = r; first = s * S->cycrho[c][q]; }
            else if (r != root || s * S->cycrho[c][q] != first) forced = 0;
        }
        if (forced) return 1;
    }
    return 0;
}

/* A piece with the region's sides `sub` (indices, repeated sides impossible) and `chords`
 * third-axis sides: add its constraints; the mark to roll back to, or -1 (nothing added). */
static int admit(Search *S, const Region *g, const int *sub, int nsub, int chords) {
    int total = nsub + chords;
    if (total < 3 || total > 6) return -1;
    int na[2] = {0, 0}, of[2][2];
    for (int a = 0; a < nsub; a++) {
        const Side *x = &g->s[sub[a]];
        for (int b = 0; b < a; b++)
            if (g->s[sub[b]].loop == x->loop) return -1;
        if (na[x->axis] == 2) return -1;
        of[x->axis][na[x->axis]++] = sub[a];
    }
    int mark = S->ntrail;
    for (int ax = 0; ax < 2; ax++) {
        if (na[ax] < 2) continue;
        const Side *p = &g->s[of[ax][0]], *q = &g->s[of[ax][1]];
        if (!relate(S, p->loop, q->loop, -p->fwd * q->fwd)) {
            rollback(S, mark);
            S->incons++;
            return -1;
        }
    }
    if (S->ntrail > mark && one_way(S)) {
        rollback(S, mark);
        S->oneway++;
        return -1;
    }
    return mark;
}

static int span(const Region *g, int i, int j, int *out) {
    int n = ((j - i) % g->ns + g->ns) % g->ns + 1;
    for (int q = 0; q < n; q++) out[q] = (i + q) % g->ns;
    return n;
}

static void free_points(const Region *g, const Walk *W, int *got) {
    got[0] = got[1] = 0;
    for (int i = 0; i < g->ns; i++) {
        if (W->fixed[i] >= 0 || !g->s[i].first) continue;
        int m = W->count[i];
        if (g->s[i].other >= 0 && W->count[g->s[i].other] > m) m = W->count[g->s[i].other];
        got[g->s[i].axis] += m;
    }
}

static int fits(Search *S, int from, const int *placed) {
    int total = 0, on[2] = {0, 0};
    for (int i = from; i < S->R; i++) {
        const Region *g = &S->reg[i];
        int fixed[2] = {0, 0};
        for (int a = 0; a < g->ns; a++)
            if (S->points[g->s[a].edge] >= 0) fixed[g->s[a].axis] += S->points[g->s[a].edge];
        int t = g->need - fixed[0] - fixed[1];
        if (t > 0) total += t;
        for (int k = 0; k < 2; k++) {
            int u = g->as[k] - 2 - fixed[1 - k];
            if (u > 0) on[1 - k] += u;
        }
    }
    int bound = (total + 1) / 2, on0 = (on[0] + 1) / 2, on1 = (on[1] + 1) / 2;
    /* four runs: each loop of B ends with points on two of its edges at least */
    int crossed[MAXL], open[MAXL], lack[2] = {0, 0};
    for (int l = 0; l < S->NL; l++) crossed[l] = open[l] = 0;
    for (int e = 0; e < S->E; e++) {
        if (S->points[e] < 0) open[S->edge_loop[e]]++;
        else if (S->points[e] > 0) crossed[S->edge_loop[e]]++;
    }
    for (int e = 0; e < S->E; e++) {
        int l = S->edge_loop[e];
        if (open[l] < 0) continue;  /* counted */
        if (crossed[l] + open[l] < 2) return 0;
        if (crossed[l] < 2) lack[S->edge_axis[e]] += 2 - crossed[l];
        open[l] = -1;
    }
    if (lack[0] > on0) on0 = lack[0];
    if (lack[1] > on1) on1 = lack[1];
    if (lack[0] + lack[1] > bound) bound = lack[0] + lack[1];
    int e0 = placed[0] + on0, e1 = placed[1] + on1;
    if (e0 < S->least) e0 = S->least;
    if (e1 < S->least) e1 = S->least;
    int need = placed[0] + placed[1] + bound;
    if (e0 + e1 > need) need = e0 + e1;
    return need <= S->budget;
}

static void choose(Search *S, int i, const int *placed);

/* The region's option is complete (counts and chords in S->w[i], S->k[i], S->ends[i]):
 * number its free edges and go on to the next region. */
static void descend(Search *S, int i) {
    const Region *g = &S->reg[i];
    Walk *W = &S->w[i];
    int now[2] = {W->placed[0], W->placed[1]};
    for (int a = 0; a < g->ns; a++) {
        if (W->fixed[a] >= 0 || !g->s[a].first) continue;
        S->points[g->s[a].edge] = W->count[a];
        now[g->s[a].axis] += W->count[a];
    }
    S->nodes++;
    if (fits(S, i + 1, now)) choose(S, i + 1, now);
    else S->over++;
    for (int a = 0; a < g->ns; a++)
        if (W->fixed[a] < 0) S->points[g->s[a].edge] = -1;
}

/* Whether the closed walk's counts meet the numbered edges, the caps, an edge on two sides,
 * and it is the walk from the lesser of its two caps. */
static int closes(const Region *g, const Walk *W) {
    for (int a = 0; a < g->ns; a++) {
        if (W->fixed[a] >= 0 && W->fixed[a] != W->count[a]) return 0;
        if (W->fixed[a] < 0 && g->s[a].other >= 0 && W->count[a] != W->count[g->s[a].other]) return 0;
    }
    int got[2];
    free_points(g, W, got);
    if (got[0] > W->cap[0] || got[1] > W->cap[1]) return 0;
    int k = W->kk;
    for (int q = 0; q < 2 * k; q++) {  /* (L, R) against (reversed R, reversed L) */
        int mine = q < k ? W->L[q] : W->Rr[q - k];
        int theirs = q < k ? W->Rr[k - 1 - q] : W->L[2 * k - 1 - q];
        if (mine != theirs) return mine < theirs;
    }
    return 1;
}

static void record_chords(Search *S, int i) {
    const Region *g = &S->reg[i];
    const Walk *W = &S->w[i];
    int k = W->kk, seq[2 * MAXK], on[MAXS];
    memset(on, 0, sizeof on);
    for (int q = 0; q < k; q++) { seq[q] = W->L[q]; seq[2 * k - 1 - q] = W->Rr[q]; }
    unsigned char end[2 * MAXK][3];
    for (int q = 0; q < 2 * k; q++) {
        const Side *x = &g->s[seq[q]];
        int rank = on[seq[q]]++;
        end[q][0] = (unsigned char)x->edge;
        end[q][1] = (unsigned char)(x->rev ? W->count[seq[q]] - 1 - rank : rank);
        end[q][2] = (unsigned char)x->rev;
    }
    S->k[i] = k;
    for (int q = 0; q < k; q++) {
        memcpy(S->ends[i][q], end[q], 3);
        memcpy(S->ends[i][q] + 3, end[2 * k - 1 - q], 3);
    }
}

static void walk(Search *S, int i, int used);

/* Put the next chord's ends on sides jL and jR, the piece it closes having the sides `sub` of
 * B (n of them) and `chords` chords: walk on from there when the points fit the numbered edges
 * and the caps, and the piece is a corner. */
static void next_chord(Search *S, int i, int jL, int jR, const int *sub, int n, int chords, int used) {
    const Region *g = &S->reg[i];
    Walk *W = &S->w[i];
    W->count[jL]++;
    W->count[jR]++;
    int ok = (W->fixed[jL] < 0 || W->count[jL] <= W->fixed[jL]) &&
             (W->fixed[jR] < 0 || W->count[jR] <= W->fixed[jR]);
    if (ok) {
        int got[2];
        free_points(g, W, got);
        ok = got[0] <= W->cap[0] && got[1] <= W->cap[1];
    }
    if (ok) {
        int mark = admit(S, g, sub, n, chords);
        if (mark >= 0) {
            W->L[W->kk] = jL;
            W->Rr[W->kk] = jR;
            W->kk++;
            walk(S, i, used);
            W->kk--;
            rollback(S, mark);
        }
    }
    W->count[jL]--;
    W->count[jR]--;
}

static void walk(Search *S, int i, int used) {
    if (S->failed) return;
    const Region *g = &S->reg[i];
    Walk *W = &S->w[i];
    int iL = W->L[W->kk - 1], iR = W->Rr[W->kk - 1], sub[2 * MAXS + 2];
    int rest = g->ns - used;
    if (rest >= 1 && rest <= 4 && closes(g, W)) {
        int n = span(g, iL, iR, sub);
        int mark = admit(S, g, sub, n, 1);
        if (mark >= 0) {
            record_chords(S, i);
            descend(S, i);
            rollback(S, mark);
        }
    }
    static const int moves[6][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 0}, {0, 2}};
    if (W->kk >= MAXK - 1) return;
    for (int m = 0; m < 6; m++) {
        int dL = moves[m][0], dR = moves[m][1];
        if (used + dL + dR > g->ns - 1) continue;
        int jL = (iL + dL) % g->ns, jR = ((iR - dR) % g->ns + g->ns) % g->ns;
        int n = span(g, iL, jL, sub);
        n += span(g, jR, iR, sub + n);
        next_chord(S, i, jL, jR, sub, n, 2, used + dL + dR);
    }
}

static void complete(Search *S);

static void choose(Search *S, int i, const int *placed) {
    if (S->failed) return;
    if (i == S->R) { complete(S); return; }
    const Region *g = &S->reg[i];
    Walk *W = &S->w[i];
    int none = 1, sub[MAXS] = {0};
    for (int a = 0; a < g->ns; a++) {
        W->fixed[a] = S->points[g->s[a].edge];
        W->count[a] = 0;
        if (W->fixed[a] > 0) none = 0;
    }
    W->placed[0] = placed[0];
    W->placed[1] = placed[1];
    int hi0 = placed[1] > S->least ? placed[1] : S->least, hi1 = placed[0] > S->least ? placed[0] : S->least;
    W->cap[0] = S->budget - hi0 - placed[0];
    W->cap[1] = S->budget - hi1 - placed[1];
    W->kk = 0;
    if (none) {  /* no chord: the region is one corner */
        for (int a = 0; a < g->ns; a++) sub[a] = a;
        int mark = admit(S, g, sub, g->ns, 0);
        if (mark >= 0) {
            S->k[i] = 0;
            descend(S, i);
            rollback(S, mark);
        }
    }
    for (int iR = 0; iR < g->ns; iR++) {
        for (int t = 1; t <= 4 && t <= g->ns - 1; t++) {
            int iL = (iR + t) % g->ns;
            int n = span(g, iR, iL, sub);
            next_chord(S, i, iL, iR, sub, n, 1, t);
        }
    }
}

/* Every region is chosen: keep the third axis when each of its loops crosses each region once
 * (the chords of one region lie on different loops). */
static int root(const int *up, int x) {
    while (up[x] != x) x = up[x];
    return x;
}

static void complete(Search *S) {
    S->complete++;
    int off[MAXE], total = 0;
    for (int e = 0; e < S->E; e++) { off[e] = total; total += S->points[e]; }
    if (total > MAXP) { S->failed = 2; return; }
    int up[MAXP];
    for (int p = 0; p < total; p++) up[p] = p;
    for (int i = 0; i < S->R; i++)
        for (int q = 0; q < S->k[i]; q++) {
            const unsigned char *c = S->ends[i][q];
            int a = root(up, off[c[0]] + c[1]), b = root(up, off[c[3]] + c[4]);
            if (a != b) up[a] = b;
        }
    for (int i = 0; i < S->R; i++)
        for (int q = 0; q < S->k[i]; q++)
            for (int r = 0; r < q; r++) {
                const unsigned char *c = S->ends[i][q], *d = S->ends[i][r];
                if (root(up, off[c[0]] + c[1]) == root(up, off[d[0]] + d[1])) return;
            }
    S->kept++;
    int size = S->E;
    for (int i = 0; i < S->R; i++) size += 2 + 6 * S->k[i];
    PyObject *b = PyBytes_FromStringAndSize(NULL, size);
    if (!b) { S->failed = 1; return; }
    unsigned char *o = (unsigned char *)PyBytes_AS_STRING(b);
    for (int e = 0; e < S->E; e++) *o++ = (unsigned char)S->points[e];
    for (int i = 0; i < S->R; i++) {
        *o++ = (unsigned char)S->reg[i].f;
        *o++ = (unsigned char)S->k[i];
        for (int q = 0; q < S->k[i]; q++) { memcpy(o, S->ends[i][q], 6); o += 6; }
    }
    if (PyList_Append(S->out, b) < 0) S->failed = 1;
    Py_DECREF(b);
}

static PyObject *systems(PyObject *self, PyObject *args) {
    Py_buffer sb;
    if (!PyArg_ParseTuple(args, "y*", &sb)) return NULL;
    const int *v = (const int *)sb.buf;
    Py_ssize_t n = sb.len / (Py_ssize_t)sizeof(int), at = 0;
    Search *S = calloc(1, sizeof(Search));
    if (!S) { PyBuffer_Release(&sb); return PyErr_NoMemory(); }
#define NEXT() (at < n ? v[at++] : (bad = 1, 0))
    int bad = 0;
    S->R = NEXT(); S->E = NEXT(); S->NL = NEXT(); S->least = NEXT(); S->budget = NEXT();
    if (S->R > MAXR || S->E > MAXE || S->NL > MAXL || S->R <= 0) bad = 1;
    for (int e = 0; e < S->E && !bad; e++) {
        S->edge_axis[e] = NEXT();
        S->edge_loop[e] = NEXT();
        S->points[e] = -1;
        if (S->edge_loop[e] < 0 || S->edge_loop[e] >= S->NL) bad = 1;
    }
    for (int i = 0; i < S->R && !bad; i++) {
        Region *g = &S->reg[i];
        g->f = NEXT(); g->ns = NEXT(); g->need = NEXT(); g->as[0] = NEXT(); g->as[1] = NEXT();
        if (g->ns > MAXS || g->ns <= 0) { bad = 1; break; }
        for (int a = 0; a < g->ns; a++) {
            Side *x = &g->s[a];
            x->edge = NEXT(); x->rev = NEXT(); x->loop = NEXT(); x->axis = NEXT(); x->fwd = NEXT();
            if (x->edge < 0 || x->edge >= S->E || x->loop < 0 || x->loop >= S->NL || x->axis < 0 || x->axis > 1)
                bad = 1;
        }
        for (int a = 0; a < g->ns && !bad; a++) {
            g->s[a].first = 1;
            g->s[a].other = -1;
            for (int b = 0; b < g->ns; b++)
                if (b != a && g->s[b].edge == g->s[a].edge) {
                    g->s[a].other = b;
                    if (b < a) g->s[a].first = 0;
                }
        }
    }
    S->ncyc = NEXT();
    if (S->ncyc > MAXCYC || S->ncyc < 0) bad = 1;
    for (int c = 0; c < S->ncyc && !bad; c++) {
        S->cyclen[c] = NEXT();
        if (S->cyclen[c] > MAXL || S->cyclen[c] <= 0) { bad = 1; break; }
        for (int q = 0; q < S->cyclen[c]; q++) { S->cycloop[c][q] = NEXT(); S->cycrho[c][q] = NEXT(); }
    }
#undef NEXT
    PyBuffer_Release(&sb);
    if (bad) { free(S); return PyErr_Format(PyExc_ValueError, "a malformed region-search specification"); }
    for (int l = 0; l < S->NL; l++) { S->parent[l] = l; S->par[l] = 1; }
    S->out = PyList_New(0);
    if (!S->out) { free(S); return NULL; }
    int placed[2] = {0, 0};
    choose(S, 0, placed);
    PyObject *result = NULL;
    if (S->failed == 1) Py_DECREF(S->out);
    else if (S->failed == 2) {
        Py_DECREF(S->out);
        PyErr_Format(PyExc_ValueError, "a third axis with too many points");
    } else
        result = Py_BuildValue("(N(LLLLLL))", S->out, S->nodes, S->over, S->incons, S->oneway, S->complete,
                               S->kept);
    free(S);
    return result;
}

static PyMethodDef methods[] = {
    {"systems", systems, METH_VARARGS,
     "systems(spec) -> (systems, (region choices, over the budget, inconsistent, one way, complete,\n"
     "kept)): every third axis for a two-axis arrangement whose pieces pass the local tests and whose\n"
     "loops cross each region once (spec and result as described in _regions.c)"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_regions", NULL, -1, methods};

PyMODINIT_FUNC PyInit__regions(void) { return PyModule_Create(&module); }
