/* Counting the simple cycles of the addition graph: the compiled twin of the search in
 * polyloops/core/moves.py (_AdditionGraph.cycles and _extend), which says what the graph is.
 *
 * count(indptr, succ, target, out_indptr, out_darts, allowed, starts, max_count, seconds)
 *     -> (count, status)
 *   indptr, succ: the graph on darts in CSR form (int32): the darts that may leave after
 *     arriving along dart d are succ[indptr[d]:indptr[d + 1]];
 *   target: the corner each dart reaches (int32);
 *   out_indptr, out_darts: the darts leaving each corner (CSR, int32);
 *   allowed: 1 for darts the new loop may cross (not of its own axis), per dart (uint8);
 *   starts: the corners to start from (int32); a cycle is counted from its lowest corner, so
 *     the starts partition the cycles;
 *   max_count: stop after this many (-1: no limit); seconds: stop after this much CPU-clock
 *     time (negative: no limit).
 *   status: 0 complete, 1 stopped by max_count, 2 stopped by the time limit.
 *
 * A cycle walks corners start = c0 < c1, ..., c(k-1) (each once, all above the start), k >= 3,
 * each step allowed by the graph, closing back to the start with the step from the last dart
 * to the first also allowed: exactly the cycles the Python search yields.
 *
 * Reentrant; runs with the GIL held.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdint.h>
#include <stdlib.h>
#include <time.h>

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + ts.tv_nsec * 1e-9;
}

static int allows(const int32_t *indptr, const int32_t *succ, int arrive, int leave) {
    for (int i = indptr[arrive]; i < indptr[arrive + 1]; i++)
        if (succ[i] == leave) return 1;
    return 0;
}

static PyObject *count(PyObject *self, PyObject *args) {
    Py_buffer bi, bs, bt, boi, bod, ba, bst;
    long long max_count;
    double seconds;
    if (!PyArg_ParseTuple(args, "y*y*y*y*y*y*y*Ld", &bi, &bs, &bt, &boi, &bod, &ba, &bst, &max_count, &seconds))
        return NULL;
    PyObject *result = NULL;
    const int32_t *indptr = bi.buf, *succ = bs.buf, *target = bt.buf, *out_indptr = boi.buf;
    const int32_t *out_darts = bod.buf, *starts = bst.buf;
    const uint8_t *allowed = ba.buf;
    int darts = (int)(bt.len / 4), corners = (int)(boi.len / 4) - 1, nstarts = (int)(bst.len / 4);
    int32_t *path = NULL, *pos = NULL;
    uint8_t *on_path = NULL;
    if (bi.len != 4 * ((Py_ssize_t)darts + 1) || ba.len != darts || corners < 0) {
        PyErr_SetString(PyExc_ValueError, "count: arrays of inconsistent lengths");
        goto done;
    }
    path = malloc(sizeof(int32_t) * (corners + 1));
    pos = malloc(sizeof(int32_t) * (corners + 1));
    on_path = calloc(corners + 1, 1);
    if (!path || !pos || !on_path) { PyErr_NoMemory(); goto done; }
    long long found = 0;
    int status = 0;
    double deadline = seconds >= 0 ? now() + seconds : -1;
    unsigned long ticks = 0;
    for (int si = 0; si < nstarts && !status; si++) {
        int start = starts[si];
        for (int oi = out_indptr[start]; oi < out_indptr[start + 1] && !status; oi++) {
            int first = out_darts[oi];
            if (!allowed[first] || target[first] <= start) continue;
            /* depth-first: path[0..len-1] are darts, pos[j] the next successor to try after path[j] */
            int len = 1;
            path[0] = first;
            pos[0] = indptr[first];
            on_path[start] = 1;
            on_path[target[first]] = 1;
            while (len > 0) {
                if (deadline >= 0 && (++ticks & 0xFFFF) == 0 && now() > deadline) { status = 2; break; }
                int last = path[len - 1];
                if (pos[len - 1] >= indptr[last + 1]) {
                    on_path[target[last]] = 0;
                    len--;
                    continue;
                }
                int nxt = succ[pos[len - 1]++];
                int w = target[nxt];
                if (w == start) {
                    if (len >= 2 && allows(indptr, succ, nxt, first)) {
                        if (max_count >= 0 && found >= max_count) { status = 1; break; }
                        found++;
                    }
                    continue;
                }
                if (w < start || on_path[w] || len + 2 > corners) continue;
                path[len] = nxt;
                pos[len] = indptr[nxt];
                on_path[w] = 1;
                len++;
            }
            for (int j = 0; j < len; j++) on_path[target[path[j]]] = 0;
            on_path[start] = 0;
        }
    }
    result = Py_BuildValue("(Li)", found, status);
done:
    free(path);
    free(pos);
    free(on_path);
    PyBuffer_Release(&bi);
    PyBuffer_Release(&bs);
    PyBuffer_Release(&bt);
    PyBuffer_Release(&boi);
    PyBuffer_Release(&bod);
    PyBuffer_Release(&ba);
    PyBuffer_Release(&bst);
    return result;
}

static PyMethodDef methods[] = {
    {"count", count, METH_VARARGS,
     "count(indptr, succ, target, out_indptr, out_darts, allowed, starts, max_count, seconds) -> "
     "(count, status): see the module comment."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_cycles",
                                    "The compiled count of the addition graph's cycles.", -1, methods};

PyMODINIT_FUNC PyInit__cycles(void) { return PyModule_Create(&module); }
