/* The canonical form of a small loop structure and its signature text: the compiled twin of
 * the tuple code in polyloops/core/canonical.py (canonical_form, _encode), which says what the
 * form is and why it is canonical.  Both give the same code, automorphism count and signature;
 * tests/test_canonical.py compares them on generated structures.
 *
 * canonical(nxt, twin, prev, base, tables, dets) -> (code, hits, dets_hit)
 *   nxt, twin, prev: the map's dart permutations (int32, n darts);
 *   base: each dart's label (direction 0..5, or axis 0..2), int32;
 *   tables: per group element, its action on labels (6 int32 each), dets: its determinant
 *   (int32, +1 or -1).
 *   For every element g and both orientations of the surface, a dart's invariant is
 *   (g(label), degree at its origin, degree at its target, size of the face on its left);
 *   the roots are the (element, orientation, dart) with the least invariant, refined by the
 *   labels around both ends of the dart; each remaining root gives a breadth-first code (per
 *   dart in order: index of next, index of twin, label), abandoned as soon as it exceeds the
 *   least so far.  Returns the least code (int32 bytes, 3n values), the number of roots that
 *   reach it (the automorphism count) and a mask of the determinants among them (bit 0: +1,
 *   bit 1: -1).
 *
 * encode(code, oriented) -> str: the signature text of a code (version 1, see canonical.py).
 *
 * Reentrant (no static state); runs with the GIL held.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    int32_t *lab;  /* the element's labels */
    int mirrored;
    int det;
} Candidate;

/* The BFS code from root; returns 1 and fills out (3n) when it is less than best, 2 when it
 * equals best, 0 when it exceeds it (out is then partly written).  best may be NULL. */
static int code_from(int n, const int32_t *succ, const int32_t *twin, const int32_t *lab, int root,
                     const int32_t *best, int32_t *out, int32_t *index, int32_t *order) {
    for (int i = 0; i < n; i++) index[i] = -1;
    int size = 1, equal = best != NULL;
    order[0] = root;
    index[root] = 0;
    for (int i = 0; i < n; i++) {
        int d = order[i];
        int e = succ[d], t = twin[d];
        if (index[e] < 0) { index[e] = size; order[size++] = e; }
        if (index[t] < 0) { index[t] = size; order[size++] = t; }
        int32_t item[3] = {index[e], index[t], lab[d]};
        for (int k = 0; k < 3; k++) {
            if (equal) {
                int32_t ref = best[3 * i + k];
                if (item[k] > ref) return 0;
                if (item[k] < ref) equal = 0;
            }
            out[3 * i + k] = item[k];
        }
    }
    return equal ? 2 : 1;
}

static PyObject *canonical(PyObject *self, PyObject *args) {
    Py_buffer bn, bt, bp, bb, btab, bdet;
    if (!PyArg_ParseTuple(args, "y*y*y*y*y*y*", &bn, &bt, &bp, &bb, &btab, &bdet)) return NULL;
    PyObject *result = NULL;
    int n = (int)(bn.len / 4), groups = (int)(bdet.len / 4);
    const int32_t *nxt = bn.buf, *twin = bt.buf, *prev = bp.buf, *base = bb.buf;
    const int32_t *tables = btab.buf, *dets = bdet.buf;
    int32_t *mem = NULL;
    Candidate *cands = NULL;
    if (n < 1 || bt.len != bn.len || bp.len != bn.len || bb.len != bn.len || btab.len != 24 * (Py_ssize_t)groups ||
        groups < 1) {
        PyErr_SetString(PyExc_ValueError, "canonical: arrays of unequal lengths");
        goto done;
    }
    for (int d = 0; d < n; d++) {
        if (nxt[d] < 0 || nxt[d] >= n || twin[d] < 0 || twin[d] >= n || prev[d] < 0 || prev[d] >= n ||
            base[d] < 0 || base[d] > 5) {
            PyErr_SetString(PyExc_ValueError, "canonical: a dart or label out of range");
            goto done;
        }
    }
    /* scratch: degree, fsize, mirror_next, rot0, rot1, index, order, labels per element,
       code, best, keys */
    size_t words = (size_t)n * (7 + 2 * 3) + (size_t)groups * n + (size_t)4 * n;
    mem = malloc(words * sizeof(int32_t));
    cands = malloc(sizeof(Candidate) * 2 * groups);
    if (!mem || !cands) { PyErr_NoMemory(); goto done; }
    int32_t *degree = mem, *fsize = degree + n, *mnext = fsize + n, *rot0 = mnext + n, *rot1 = rot0 + n;
    int32_t *index = rot1 + n, *order = index + n, *code = order + n, *best = code + 3 * n;
    int32_t *labs = best + 3 * n, *key = labs + (size_t)groups * n, *bestkey = key + 2 * n;
    for (int d = 0; d < n; d++) {
        rot0[d] = twin[prev[d]];
        rot1[d] = nxt[twin[d]];
        mnext[d] = twin[prev[twin[d]]];
        degree[d] = 0;
        fsize[d] = 0;
    }
    for (int d = 0; d < n; d++) {  /* orbit lengths: corners (rot0) and faces (nxt) */
        if (!degree[d]) {
            int k = 0, e = d;
            do { k++; e = rot0[e]; } while (e != d);
            e = d;
            do { degree[e] = k; e = rot0[e]; } while (e != d);
        }
        if (!fsize[d]) {
            int k = 0, e = d;
            do { k++; e = nxt[e]; } while (e != d);
            e = d;
            do { fsize[e] = k; e = nxt[e]; } while (e != d);
        }
    }
    int ncand = 0;
    for (int g = 0; g < groups; g++) {
        int32_t *lab = labs + (size_t)g * n;
        for (int d = 0; d < n; d++) lab[d] = tables[6 * g + base[d]];
        for (int m = 0; m < 2; m++) cands[ncand++] = (Candidate){lab, m, dets[g]};
    }
    /* the least invariant over every candidate */
    int64_t least = INT64_MAX;
    int64_t big = 1;
    for (int d = 0; d < n; d++) {
        if (degree[d] + 1 > big) big = degree[d] + 1;
        if (fsize[d] + 1 > big) big = fsize[d] + 1;
    }
#define INVARIANT(c, d) ((((int64_t)(c)->lab[d] * big + degree[d]) * big + degree[twin[d]]) * big + \
                         ((c)->mirrored ? fsize[twin[d]] : fsize[d]))
    for (int c = 0; c < ncand; c++)
        for (int d = 0; d < n; d++) {
            int64_t v = INVARIANT(&cands[c], d);
            if (v < least) least = v;
        }
    /* the least key (labels around both ends) among roots with the least invariant */
    int keylen = -1, have_key = 0;
    for (int c = 0; c < ncand; c++) {
        const int32_t *rot = cands[c].mirrored ? rot1 : rot0;
        for (int r = 0; r < n; r++) {
            if (INVARIANT(&cands[c], r) != least) continue;
            int len = 0;
            int ends[2] = {r, twin[r]};
            for (int s = 0; s < 2; s++) {
                int e = ends[s];
                do { key[len++] = cands[c].lab[e]; e = rot[e]; } while (e != ends[s]);
            }
            keylen = len;  /* the same for every root: both degrees are part of the invariant */
            int cmp = 0;
            if (have_key)
                for (int i = 0; i < len && !cmp; i++) cmp = key[i] < bestkey[i] ? -1 : key[i] > bestkey[i];
            if (!have_key || cmp < 0) { memcpy(bestkey, key, sizeof(int32_t) * len); have_key = 1; }
        }
    }
    /* codes from the roots with the least key */
    int hits = 0, have_best = 0, dmask = 0;
    for (int c = 0; c < ncand; c++) {
        const int32_t *rot = cands[c].mirrored ? rot1 : rot0;
        const int32_t *succ = cands[c].mirrored ? mnext : nxt;
        for (int r = 0; r < n; r++) {
            if (INVARIANT(&cands[c], r) != least) continue;
            int len = 0, same = 1;
            int ends[2] = {r, twin[r]};
            for (int s = 0; s < 2 && same; s++) {
                int e = ends[s];
                do {
                    if (cands[c].lab[e] != bestkey[len++]) { same = 0; break; }
                    e = rot[e];
                } while (e != ends[s]);
            }
            if (!same || len != keylen) continue;
            int got = code_from(n, succ, twin, cands[c].lab, r, have_best ? best : NULL, code, index, order);
            if (got == 1) {
                memcpy(best, code, sizeof(int32_t) * 3 * n);
                have_best = 1;
                hits = 1;
                dmask = cands[c].det > 0 ? 1 : 2;
            } else if (got == 2) {
                hits++;
                dmask |= cands[c].det > 0 ? 1 : 2;
            }
        }
    }
#undef INVARIANT
    result = Py_BuildValue("(y#ii)", (const char *)best, (Py_ssize_t)(sizeof(int32_t) * 3 * n), hits, dmask);
done:
    free(mem);
    free(cands);
    PyBuffer_Release(&bn);
    PyBuffer_Release(&bt);
    PyBuffer_Release(&bp);
    PyBuffer_Release(&bb);
    PyBuffer_Release(&btab);
    PyBuffer_Release(&bdet);
    return result;
}

static const char ALPHABET[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_";
#define CHECK_MODULUS 4093

static int value_of(char ch) { return (int)(strchr(ALPHABET, ch) - ALPHABET); }

static char *put_digits(char *out, long x, int w) {
    for (int j = w - 1; j >= 0; j--) out[j] = ALPHABET[x & 63], x >>= 6;
    return out + w;
}

static PyObject *encode(PyObject *self, PyObject *args) {
    Py_buffer bc;
    int oriented;
    if (!PyArg_ParseTuple(args, "y*p", &bc, &oriented)) return NULL;
    const int32_t *code = bc.buf;
    long n = (long)(bc.len / 12);
    int w = 1;
    long power = 64;
    while (power <= n) w++, power *= 64;
    size_t cap = 3 + (size_t)w + (size_t)n * (1 + 2 * (size_t)w) + 2;
    char *text = malloc(cap + 1), *p = text;
    if (!text) { PyBuffer_Release(&bc); return PyErr_NoMemory(); }
    *p++ = '1';
    *p++ = oriented ? 'o' : 'l';
    *p++ = ALPHABET[w];
    p = put_digits(p, n, w);
    long seen = 1;
    for (long i = 0; i < n; i++) {
        int flags = 0;
        long refs[2], nrefs = 0;
        for (int k = 0; k < 2; k++) {
            long ref = code[3 * i + k];
            if (ref == seen) flags |= 1 << k, seen++;
            else refs[nrefs++] = ref;
        }
        long lab = code[3 * i + 2];
        if (lab < 0 || lab > 15 || code[3 * i] < 0 || code[3 * i + 1] < 0) {
            free(text);
            PyBuffer_Release(&bc);
            PyErr_SetString(PyExc_ValueError, "encode: not a canonical code");
            return NULL;
        }
        *p++ = ALPHABET[lab * 4 + flags];
        for (long k = 0; k < nrefs; k++) p = put_digits(p, refs[k], w);
    }
    long total = 0;
    for (long i = 0; i < p - text; i++) total += (i % (CHECK_MODULUS - 1) + 1) * (long)value_of(text[i]);
    p = put_digits(p, total % CHECK_MODULUS, 2);
    PyObject *out = PyUnicode_FromStringAndSize(text, p - text);
    free(text);
    PyBuffer_Release(&bc);
    return out;
}

static PyMethodDef methods[] = {
    {"canonical", canonical, METH_VARARGS,
     "canonical(nxt, twin, prev, base, tables, dets) -> (code, hits, dets_hit): see the module comment."},
    {"encode", encode, METH_VARARGS, "encode(code, oriented) -> the signature text of a canonical code."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_canonical",
                                    "The compiled canonical form of small loop structures.", -1, methods};

PyMODINIT_FUNC PyInit__canonical(void) { return PyModule_Create(&module); }
