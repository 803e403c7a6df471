/* The compiled twin of the numpy batch filter in quadrangulations.py.
 *
 * Input: records of plantri's 1-byte planar code for quadrangulations with n vertices, each
 * 5n - 7 bytes (n, then each vertex's neighbours in clockwise order, 1-based, ending with 0).
 * A map survives when every strip (dual loop) is simple and no vertex has degree above the
 * given bound.  The function returns the surviving records, concatenated, and the number of
 * maps whose strips are all simple whatever their degrees (a count of its own interest).
 *
 * Darts are numbered in record order: the i-th neighbour of vertex v is dart start[v] + i.
 * In a face, from the dart u->v the next dart is v->w with w the clockwise successor of u
 * at v.  A strip enters a quad through one edge and leaves through the opposite one, so the
 * strip continues from dart d to twin(next(next(d))).  A face is a self-crossing when the
 * strips through two consecutive edges are the same; the walk stops at the first one, which
 * in almost every map comes early.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <string.h>

#define MAXN 255
#define MAXD (4 * MAXN)

/* next(e): at v = target(e), the dart to the clockwise successor of u = origin(e). */
#define NEXT(e) next_dart(e, twin, origin, start, deg)

static inline int next_dart(int e, const int *twin, const int *origin, const int *start, const int *deg)
{
    int t = twin[e], v = origin[t], i = t - start[v] + 1;
    return start[v] + (i == deg[v] ? 0 : i);
}

static int check_map(const unsigned char *rec, int n, int max_degree, int *index, int *simple)
{
    int start[MAXN + 1], deg[MAXN + 1];
    int origin[MAXD], target[MAXD], twin[MAXD], strip[MAXD];
    int darts = 0, maxdeg = 0;
    const unsigned char *p = rec + 1, *end = rec + 5 * n - 7;

    for (int v = 0; v < n; v++) {
        start[v] = darts;
        while (p < end && *p) {
            if (darts >= MAXD || *p > n) return -1;
            origin[darts] = v;
            target[darts] = *p - 1;
            index[v * n + *p - 1] = darts; /* dart u->v; stale entries are checked below */
            darts++;
            p++;
        }
        if (p >= end) return -1;
        p++;
        deg[v] = darts - start[v];
        if (deg[v] > maxdeg) maxdeg = deg[v];
        if (deg[v] == 0) return -1;
    }
    start[n] = darts;
    if (darts != 4 * n - 8) return -1;
    for (int d = 0; d < darts; d++) {
        int t = index[target[d] * n + origin[d]];
        /* index may hold a dart of an earlier map where this one has no reverse edge */
        if (t < 0 || t >= darts || origin[t] != target[d] || target[t] != origin[d]) return -1;
        twin[d] = t;
    }
    /* Walk each strip once, labelling both darts of its edges with its first dart.  Entering
     * a face through e, the other strip of the face crosses the edges of next(e) and
     * next(next(next(e))): if those carry the current label, this strip crosses itself here
     * (a strip passes each of its edges once, so it cannot meet a face twice the same way). */
    for (int d = 0; d < darts; d++) strip[d] = -1;
    *simple = 0;
    for (int d = 0; d < darts; d++) {
        if (strip[d] >= 0) continue;
        int e = d;
        while (strip[e] < 0) {
            strip[e] = d;
            strip[twin[e]] = d;
            int f = NEXT(e);
            if (strip[f] == d) return 0;
            e = twin[NEXT(f)];
        }
    }
    *simple = 1;
    return maxdeg <= max_degree;
}

static PyObject *filter_maps(PyObject *self, PyObject *args)
{
    Py_buffer buf;
    int n, max_degree;
    if (!PyArg_ParseTuple(args, "y*ii", &buf, &n, &max_degree)) return NULL;
    Py_ssize_t size = 5 * (Py_ssize_t)n - 7;
    if (n < 4 || n > MAXN || buf.len % size) {
        PyBuffer_Release(&buf);
        return PyErr_Format(PyExc_ValueError, "not whole planar-code records of %d vertices", n);
    }
    Py_ssize_t count = buf.len / size, kept = 0, simple_count = 0;
    unsigned char *out = PyMem_Malloc(buf.len ? buf.len : 1);
    int *index = PyMem_Calloc((size_t)n * n, sizeof(int));
    if (!out || !index) {
        PyMem_Free(out);
        PyMem_Free(index);
        PyBuffer_Release(&buf);
        return PyErr_NoMemory();
    }
    const unsigned char *data = buf.buf;
    int bad = 0;
    Py_BEGIN_ALLOW_THREADS
    for (Py_ssize_t k = 0; k < count; k++) {
        const unsigned char *rec = data + k * size;
        int simple = 0, ok;
        if (rec[0] != n || rec[size - 1] != 0) { bad = 1; break; }
        ok = check_map(rec, n, max_degree, index, &simple);
        if (ok < 0) { bad = 1; break; }
        simple_count += simple;
        if (ok) memcpy(out + size * kept++, rec, size);
    }
    Py_END_ALLOW_THREADS
    PyBuffer_Release(&buf);
    PyMem_Free(index);
    if (bad) {
        PyMem_Free(out);
        return PyErr_Format(PyExc_ValueError, "a record is not planar code of a %d-vertex quadrangulation", n);
    }
    PyObject *result = Py_BuildValue("y#n", (const char *)out, size * kept, simple_count);
    PyMem_Free(out);
    return result;
}

static PyMethodDef methods[] = {
    {"filter_maps", filter_maps, METH_VARARGS,
     "filter_maps(records, n, max_degree) -> (surviving records, number with all strips simple)"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_strips", NULL, -1, methods};

PyMODINIT_FUNC PyInit__strips(void) { return PyModule_Create(&module); }
