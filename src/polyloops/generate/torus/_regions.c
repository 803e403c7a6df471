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
 * A region's walks depend only on the points already numbered on its sides and on the budget
 * left on each axis, and the search meets each such numbering of a region many times (about
 * ten times on average for B of 16 crossings), so its options are listed once (the memo: each
 * option's points, chords and parity constraints) and each visit adds an option's constraints
 * at once: the same options pass as when they are added piece by piece along the walk (whether
 * constraints contradict does not depend on their order, and a cycle forced one way stays
 * forced), only the counts of cut options differ.  A numbering with more than `max_options`
 * options (50,000 unless the caller says) is walked directly every time instead, adding each
 * piece's constraints as it goes.
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
#include <stdlib.h>
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

typedef struct {  /* a memo entry: a region's options for one numbering of its sides and caps */
    unsigned long long hash;
    size_t key;     /* arena offset of the key: region, cap[0], cap[1], fixed[0..ns) */
    size_t first;   /* arena offset of its options, one after another */
    size_t end;
    int direct;     /* 1: too many options to list: walked directly each time */
} Memo;

#define MAXOPTIONS 50000     /* a region's options listed at most for one numbering (more: walked directly) */
#define MAXARENA (1L << 24)  /* ints in the memo at most (64 MB; new numberings then walked directly) */

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
    int occ[MAXE][2], nocc[MAXE];           /* per edge: the regions with a side on it, once a side */
    int rfixed[MAXR][2];                    /* per region: the points numbered on its sides, per axis */
    int lopen[MAXL], lcrossed[MAXL];        /* per loop: its edges not numbered, and numbered with points */
    int laxis[MAXL], lused[MAXL];           /* per loop: its axis, and whether the regions use an edge of it */
    int parent[MAXL], par[MAXL];            /* the parity union-find of loop signs (Condition 3) */
    int trail[MAXL], ntrail;                /* its unions, to roll back on the way up */
    int k[MAXR];                            /* per region: the chords of its chosen option */
    unsigned char ends[MAXR][MAXK][6];      /* per region and chord: (edge, index, reverse) x 2 */
    Walk w[MAXR];                           /* per region: its walk */
    long long nodes, over, incons, oneway, complete, kept;  /* counts returned to the caller:
        region options, branches over the budget, inconsistent signs, cycles forced one way,
        complete third axes, and those kept (each of their loops crossing each region once) */
    int rel[3 * 2 * MAXK + 6], nrel;        /* while a region's options are listed: the relations of
                                               the pieces walked so far (loop, loop, parity) */
    int *arena;                             /* the memo: keys and options, as ints */
    size_t used, room;
    Memo *memo;                             /* its hash table (open addressing) */
    int listing;                            /* 1 while a region's options are listed */
    long max_options;                       /* options listed at most for one numbering */
    long listed;                            /* options listed so far for this entry */
    int overflow;                           /* 1: too many, the list is given up */
    size_t nmemo, memo_room;
    PyObject *out;  /* the list of third axes found */
    int failed;     /* 1: a Python error is set; 2: a third axis with too many points; 3: out of memory */
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
 * third-axis sides: whether it can be a corner (3 to 6 sides, at most two of each axis of B,
 * no two on one loop); if so its parity constraints (Condition 3) are pushed on S->rel. */
static int shape(Search *S, const Region *g, const int *sub, int nsub, int chords) {
    int total = nsub + chords;
    if (total < 3 || total > 6) return 0;
    int na[2] = {0, 0}, of[2][2];
    for (int a = 0; a < nsub; a++) {
        const Side *x = &g->s[sub[a]];
        for (int b = 0; b < a; b++)
            if (g->s[sub[b]].loop == x->loop) return 0;
        if (na[x->axis] == 2) return 0;
        of[x->axis][na[x->axis]++] = sub[a];
    }
    for (int ax = 0; ax < 2; ax++) {
        if (na[ax] < 2) continue;
        const Side *p = &g->s[of[ax][0]], *q = &g->s[of[ax][1]];
        S->rel[S->nrel++] = p->loop;
        S->rel[S->nrel++] = q->loop;
        S->rel[S->nrel++] = -p->fwd * q->fwd;
    }
    return 1;
}

/* Add an option's parity constraints: the mark to roll back to, or -1 (nothing added) when they
 * contradict the others or force a cycle of a level graph one way round.  The constraints of
 * all its pieces at once: a walk that added them piece by piece would stop at the same options
 * (consistency does not depend on the order, and a forced cycle stays forced). */
static int admit(Search *S, const int *rel, int nrel) {
    int mark = S->ntrail;
    for (int r = 0; r < nrel; r++)
        if (!relate(S, rel[3 * r], rel[3 * r + 1], rel[3 * r + 2])) {
            rollback(S, mark);
            S->incons++;
            return -1;
        }
    if (S->ntrail > mark && one_way(S)) {
        rollback(S, mark);
        S->oneway++;
        return -1;
    }
    return mark;
}

/* The sides from i to j forwards round the region (indices below ns: no division, which
 * dominated the walk). */
static int span(const Region *g, int i, int j, int *out) {
    int n = j - i + (j < i ? g->ns : 0) + 1;
    for (int q = 0; q < n; q++) {
        out[q] = i;
        if (++i == g->ns) i = 0;
    }
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

/* Number edge e with c points, and undo it: the sums fits reads follow. */
static void number(Search *S, int e, int c) {
    S->points[e] = c;
    for (int q = 0; q < S->nocc[e]; q++) S->rfixed[S->occ[e][q]][S->edge_axis[e]] += c;
    S->lopen[S->edge_loop[e]]--;
    if (c > 0) S->lcrossed[S->edge_loop[e]]++;
}

static void unnumber(Search *S, int e) {
    int c = S->points[e];
    S->points[e] = -1;
    for (int q = 0; q < S->nocc[e]; q++) S->rfixed[S->occ[e][q]][S->edge_axis[e]] -= c;
    S->lopen[S->edge_loop[e]]++;
    if (c > 0) S->lcrossed[S->edge_loop[e]]--;
}

static int fits(Search *S, int from, const int *placed) {
    int total = 0, on[2] = {0, 0};
    for (int i = from; i < S->R; i++) {
        const Region *g = &S->reg[i];
        const int *fixed = S->rfixed[i];
        int t = g->need - fixed[0] - fixed[1];
        if (t > 0) total += t;
        for (int k = 0; k < 2; k++) {
            int u = g->as[k] - 2 - fixed[1 - k];
            if (u > 0) on[1 - k] += u;
        }
    }
    int bound = (total + 1) / 2, on0 = (on[0] + 1) / 2, on1 = (on[1] + 1) / 2;
    /* four runs: each loop of B ends with points on two of its edges at least */
    int lack[2] = {0, 0};
    for (int l = 0; l < S->NL; l++) {
        if (!S->lused[l]) continue;
        if (S->lcrossed[l] + S->lopen[l] < 2) return 0;
        if (S->lcrossed[l] < 2) lack[S->laxis[l]] += 2 - S->lcrossed[l];
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
        number(S, g->s[a].edge, W->count[a]);
        now[g->s[a].axis] += W->count[a];
    }
    S->nodes++;
    if (fits(S, i + 1, now)) choose(S, i + 1, now);
    else S->over++;
    for (int a = 0; a < g->ns; a++)
        if (W->fixed[a] < 0 && g->s[a].first) unnumber(S, g->s[a].edge);
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

static int grow(Search *S, size_t more) {
    if (S->used + more <= S->room) return 1;
    size_t room = S->room ? S->room : 1 << 16;
    while (room < S->used + more) room *= 2;
    int *a = realloc(S->arena, room * sizeof(int));
    if (!a) { S->failed = 3; return 0; }
    S->arena = a;
    S->room = room;
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

/* Append the closed walk as an option: k, the relations' count, each side's points, the chords'
 * ends (edge, index, reverse) x 2, the relations; or give up the list when it grows too long. */
static void record_option(Search *S, int i) {
    const Region *g = &S->reg[i];
    int k = S->w[i].kk, nr = S->nrel / 3;
    size_t size = 2 + (size_t)g->ns + 6 * (size_t)k + 3 * (size_t)nr;
    if (++S->listed > S->max_options || S->used + size > MAXARENA) { S->overflow = 1; return; }
    if (!grow(S, size)) return;
    record_chords(S, i);
    int *o = S->arena + S->used;
    *o++ = k;
    *o++ = nr;
    for (int a = 0; a < g->ns; a++) *o++ = S->w[i].count[a];
    for (int q = 0; q < k; q++)
        for (int t = 0; t < 6; t++) *o++ = S->ends[i][q][t];
    for (int r = 0; r < 3 * nr; r++) *o++ = S->rel[r];
    S->used = (size_t)(o - S->arena);
}

/* A closed walk or a whole region's piece (its constraints on S->rel from `top`): listed, or,
 * walking directly, admitted and followed by the next region. */
static void closed(Search *S, int i, int top) {
    if (S->listing) { record_option(S, i); return; }
    int mark = admit(S, S->rel + top, (S->nrel - top) / 3);
    if (mark < 0) return;
    record_chords(S, i);
    descend(S, i);
    rollback(S, mark);
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
    int top = S->nrel;
    if (ok && shape(S, g, sub, n, chords)) {
        /* walking directly, a piece's constraints are added at once: a walk stops at the first
         * piece they rule out */
        int mark = S->listing ? 0 : admit(S, S->rel + top, (S->nrel - top) / 3);
        if (mark >= 0) {
            W->L[W->kk] = jL;
            W->Rr[W->kk] = jR;
            W->kk++;
            walk(S, i, used);
            W->kk--;
            if (!S->listing) rollback(S, mark);
        }
    }
    S->nrel = top;
    W->count[jL]--;
    W->count[jR]--;
}

static void walk(Search *S, int i, int used) {
    if (S->failed || S->overflow) return;
    const Region *g = &S->reg[i];
    Walk *W = &S->w[i];
    int iL = W->L[W->kk - 1], iR = W->Rr[W->kk - 1], sub[2 * MAXS + 2];
    int rest = g->ns - used;
    if (rest >= 1 && rest <= 4 && closes(g, W)) {
        int n = span(g, iL, iR, sub), top = S->nrel;
        if (shape(S, g, sub, n, 1)) closed(S, i, top);
        S->nrel = top;
    }
    static const int moves[6][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 0}, {0, 2}};
    if (W->kk >= MAXK - 1) return;
    for (int m = 0; m < 6; m++) {
        int dL = moves[m][0], dR = moves[m][1];
        if (used + dL + dR > g->ns - 1) continue;
        int jL = iL + dL, jR = iR - dR;  /* dL, dR < ns */
        if (jL >= g->ns) jL -= g->ns;
        if (jR < 0) jR += g->ns;
        int n = span(g, iL, jL, sub);
        n += span(g, jR, iR, sub + n);
        next_chord(S, i, jL, jR, sub, n, 2, used + dL + dR);
    }
}

static void complete(Search *S);

/* Walk region i for the numbering and caps in S->w[i]: listing its options into the arena
 * (their parity constraints are the caller's), or directly, going on to the next region from
 * each option that the constraints so far admit. */
static void walk_region(Search *S, int i) {
    const Region *g = &S->reg[i];
    Walk *W = &S->w[i];
    int none = 1, sub[MAXS] = {0};
    for (int a = 0; a < g->ns; a++) {
        W->count[a] = 0;
        if (W->fixed[a] > 0) none = 0;
    }
    W->kk = 0;
    S->nrel = 0;
    if (none) {  /* no chord: the region is one corner */
        for (int a = 0; a < g->ns; a++) sub[a] = a;
        if (shape(S, g, sub, g->ns, 0)) closed(S, i, 0);
        S->nrel = 0;
    }
    for (int iR = 0; iR < g->ns; iR++) {
        for (int t = 1; t <= 4 && t <= g->ns - 1; t++) {
            int iL = iR + t < g->ns ? iR + t : iR + t - g->ns;
            int n = span(g, iR, iL, sub);
            next_chord(S, i, iL, iR, sub, n, 1, t);
        }
    }
}

/* The memo entry of region i's options for the numbering and caps in S->w[i], listed first
 * when new: the walks depend on nothing else, and the search meets each numbering of a region
 * many times (about ten on average at 16 crossings). */
static const Memo *options(Search *S, int i) {
    const Region *g = &S->reg[i];
    const Walk *W = &S->w[i];
    int klen = 3 + g->ns, key[3 + MAXS];
    key[0] = i; key[1] = W->cap[0]; key[2] = W->cap[1];
    for (int a = 0; a < g->ns; a++) key[3 + a] = W->fixed[a];
    unsigned long long h = 1469598103934665603ULL;
    for (int q = 0; q < klen; q++) h = (h ^ (unsigned long long)(unsigned)key[q]) * 1099511628211ULL;
    if (2 * (S->nmemo + 1) > S->memo_room) {  /* grow the table and place the entries again */
        size_t room = S->memo_room ? 2 * S->memo_room : 1024;
        Memo *t = calloc(room, sizeof(Memo));
        if (!t) { S->failed = 3; return NULL; }
        for (size_t q = 0; q < S->memo_room; q++) {
            if (!S->memo[q].hash) continue;
            size_t at = S->memo[q].hash & (room - 1);
            while (t[at].hash) at = (at + 1) & (room - 1);
            t[at] = S->memo[q];
        }
        free(S->memo);
        S->memo = t;
        S->memo_room = room;
    }
    h |= 1;  /* 0 marks an empty slot */
    size_t at = h & (S->memo_room - 1);
    for (; S->memo[at].hash; at = (at + 1) & (S->memo_room - 1))
        if (S->memo[at].hash == h && !memcmp(S->arena + S->memo[at].key, key, (size_t)klen * sizeof(int)))
            return &S->memo[at];
    if (!grow(S, (size_t)klen)) return NULL;
    memcpy(S->arena + S->used, key, (size_t)klen * sizeof(int));
    Memo m = {h, S->used, 0, 0, 0};
    S->used += (size_t)klen;
    m.first = S->used;
    S->listing = 1;
    S->listed = 0;
    S->overflow = 0;
    walk_region(S, i);
    S->listing = 0;
    if (S->failed) return NULL;
    if (S->overflow) {  /* forget the options listed: this numbering is walked directly */
        S->overflow = 0;
        S->used = m.first;
        m.direct = 1;
    }
    m.end = S->used;
    S->memo[at] = m;
    S->nmemo++;
    return &S->memo[at];
}

static void choose(Search *S, int i, const int *placed) {
    if (S->failed) return;
    if (i == S->R) { complete(S); return; }
    const Region *g = &S->reg[i];
    Walk *W = &S->w[i];
    for (int a = 0; a < g->ns; a++) W->fixed[a] = S->points[g->s[a].edge];
    W->placed[0] = placed[0];
    W->placed[1] = placed[1];
    int hi0 = placed[1] > S->least ? placed[1] : S->least, hi1 = placed[0] > S->least ? placed[0] : S->least;
    W->cap[0] = S->budget - hi0 - placed[0];
    W->cap[1] = S->budget - hi1 - placed[1];
    W->kk = 0;
    const Memo *m = options(S, i);
    if (!m) return;
    if (m->direct) {
        walk_region(S, i);
        return;
    }
    size_t at = m->first, end = m->end;  /* offsets: the arena may move while deeper regions list theirs */
    while (at < end && !S->failed) {
        const int *o = S->arena + at;
        int k = o[0], nr = o[1];
        at += 2 + (size_t)g->ns + 6 * (size_t)k + 3 * (size_t)nr;
        int mark = admit(S, o + 2 + g->ns + 6 * k, nr);
        if (mark < 0) continue;
        for (int a = 0; a < g->ns; a++) W->count[a] = o[2 + a];
        S->k[i] = k;
        for (int q = 0; q < k; q++)
            for (int t = 0; t < 6; t++) S->ends[i][q][t] = (unsigned char)o[2 + g->ns + 6 * q + t];
        descend(S, i);
        rollback(S, mark);
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
    long max_options = MAXOPTIONS;
    if (!PyArg_ParseTuple(args, "y*|l", &sb, &max_options)) return NULL;
    const int *v = (const int *)sb.buf;
    Py_ssize_t n = sb.len / (Py_ssize_t)sizeof(int), at = 0;
    Search *S = calloc(1, sizeof(Search));
    if (!S) { PyBuffer_Release(&sb); return PyErr_NoMemory(); }
    S->max_options = max_options;
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
    for (int e = 0; e < S->E; e++) {  /* every edge free: the sums fits reads */
        S->lopen[S->edge_loop[e]]++;
        S->lused[S->edge_loop[e]] = 1;
        S->laxis[S->edge_loop[e]] = S->edge_axis[e];
    }
    for (int i = 0; i < S->R; i++)
        for (int a = 0; a < S->reg[i].ns; a++) {
            int e = S->reg[i].s[a].edge;
            if (S->nocc[e] < 2) S->occ[e][S->nocc[e]++] = i;
            else bad = 1;  /* an edge has two sides */
        }
    if (bad) { free(S); return PyErr_Format(PyExc_ValueError, "a malformed region-search specification"); }
    S->out = PyList_New(0);
    if (!S->out) { free(S); return NULL; }
    int placed[2] = {0, 0};
    choose(S, 0, placed);
    PyObject *result = NULL;
    if (S->failed == 1) Py_DECREF(S->out);
    else if (S->failed == 3) {
        Py_DECREF(S->out);
        PyErr_NoMemory();
    }
    else if (S->failed == 2) {
        Py_DECREF(S->out);
        PyErr_Format(PyExc_ValueError, "a third axis with too many points");
    } else
        result = Py_BuildValue("(N(LLLLLL))", S->out, S->nodes, S->over, S->incons, S->oneway, S->complete,
                               S->kept);
    free(S->arena);
    free(S->memo);
    free(S);
    return result;
}

static PyMethodDef methods[] = {
    {"systems", systems, METH_VARARGS,
     "systems(spec, max_options=50000) -> (systems, (region choices, over the budget, inconsistent, one way,\n"
     "complete, kept)): every third axis for a two-axis arrangement whose pieces pass the local tests and whose\n"
     "loops cross each region once (spec and result as described in _regions.c)"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_regions", NULL, -1, methods};

PyMODINIT_FUNC PyInit__regions(void) { return PyModule_Create(&module); }
