/* The depth buffer of a polycube's triangles: the compiled twin of the triangle-at-a-time
 * loop in polyloops/render/raster.py (_triangle), which says what the test is.
 *
 * fill(tris, u, v, left, top, step, tie, face, depth, point) -> None
 *   tris: per triangle, in drawing order, 19 float64: xa ya xb yb xc yc da db dc f, the
 *     corners' view coordinates and depths and the face id (an integer value), then the
 *     corners' 3D points (a b c, x y z each);
 *   u, v: the pixel centres' view coordinates along a row and down a column (float64, n each);
 *   left, top, step: the picture's left and top edges and the pixel size;
 *   tie: how much nearer a later triangle must be to win a pixel;
 *   face (int64), depth (float64): n * n each, point (float64): n * n * 3, the 3D point
 *     seen; row-major, written in place.
 *
 * The arithmetic is the Python loop's, operation for operation (no reassociation), so the
 * two give the same buffers bit for bit; tests/test_render.py compares them.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>
#include <stdint.h>

static double min3(double a, double b, double c) { return a < b ? (a < c ? a : c) : (b < c ? b : c); }
static double max3(double a, double b, double c) { return a > b ? (a > c ? a : c) : (b > c ? b : c); }

static PyObject *fill(PyObject *self, PyObject *args) {
    Py_buffer bt, bu, bv, bf, bd, bp;
    double left, top, step, tie;
    if (!PyArg_ParseTuple(args, "y*y*y*ddddw*w*w*", &bt, &bu, &bv, &left, &top, &step, &tie, &bf, &bd, &bp))
        return NULL;
    PyObject *result = NULL;
    const double *tris = bt.buf, *u = bu.buf, *v = bv.buf;
    int64_t *face = bf.buf;
    double *depth = bd.buf, *point = bp.buf;
    Py_ssize_t n = bu.len / 8, count = bt.len / (19 * 8);
    if (bv.len != bu.len || bt.len % (19 * 8) || bf.len != 8 * n * n || bd.len != bf.len
        || bp.len != 3 * bf.len) {
        PyErr_SetString(PyExc_ValueError, "fill: arrays of inconsistent lengths");
        goto done;
    }
    for (Py_ssize_t t = 0; t < count; t++) {
        const double *r = tris + 19 * t, *pa = r + 10, *pb = r + 13, *pc = r + 16;
        double xa = r[0], ya = r[1], xb = r[2], yb = r[3], xc = r[4], yc = r[5];
        double da = r[6], db = r[7], dc = r[8];
        double area = (xb - xa) * (yc - ya) - (xc - xa) * (yb - ya);
        if (fabs(area) < 1e-12) continue; /* seen edge-on: covers no pixel centre */
        double fj0 = floor((min3(xa, xb, xc) - left) / step), fj1 = ceil((max3(xa, xb, xc) - left) / step) + 1;
        double fi0 = floor((top - max3(ya, yb, yc)) / step), fi1 = ceil((top - min3(ya, yb, yc)) / step) + 1;
        Py_ssize_t j0 = fj0 < 0 ? 0 : (Py_ssize_t)fj0, i0 = fi0 < 0 ? 0 : (Py_ssize_t)fi0;
        Py_ssize_t j1 = fj1 > (double)n ? n : (Py_ssize_t)fj1, i1 = fi1 > (double)n ? n : (Py_ssize_t)fi1;
        for (Py_ssize_t i = i0; i < i1; i++) {
            double py = v[i];
            for (Py_ssize_t j = j0; j < j1; j++) {
                double px = u[j];
                /* barycentric coordinates from edge functions; a centre on an edge is inside */
                double wa = ((xb - px) * (yc - py) - (xc - px) * (yb - py)) / area;
                double wb = ((xc - px) * (ya - py) - (xa - px) * (yc - py)) / area;
                double wc = 1.0 - wa - wb;
                if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9) continue;
                double d = wa * da + wb * db + wc * dc;
                Py_ssize_t k = i * n + j;
                if (d > depth[k] + tie) {
                    depth[k] = d;
                    face[k] = (int64_t)r[9];
                    for (int e = 0; e < 3; e++) point[3 * k + e] = wa * pa[e] + wb * pb[e] + wc * pc[e];
                }
            }
        }
    }
    Py_INCREF(Py_None);
    result = Py_None;
done:
    PyBuffer_Release(&bt);
    PyBuffer_Release(&bu);
    PyBuffer_Release(&bv);
    PyBuffer_Release(&bf);
    PyBuffer_Release(&bd);
    PyBuffer_Release(&bp);
    return result;
}

static PyMethodDef methods[] = {
    {"fill", fill, METH_VARARGS,
     "fill(tris, u, v, left, top, step, tie, face, depth, point) -> None: see the module comment."},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {PyModuleDef_HEAD_INIT, "_raster",
                                    "The compiled depth buffer of a polycube's triangles.", -1, methods};

PyMODINIT_FUNC PyInit__raster(void) { return PyModule_Create(&module); }
