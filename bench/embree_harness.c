/* embree_harness.c — Embree 3 (Debian's libembree-dev) as a query server for bench/embree.py.
 *
 * Why C: the `embreex` binding (Embree 4.4) builds triangle meshes only; Embree's true sphere
 * (RTC_GEOMETRY_TYPE_SPHERE_POINT: a centre and a radius, no tessellation) is reached only
 * through the C API. This program does nothing but hold one Embree scene and answer batches of
 * rays; every ray (the camera's, the reflected ones, the shadow segments) is made by embree.py
 * in f64, so the rules that pick the rays live in one place for both peers.
 *
 * Protocol, little-endian binary on stdin / stdout (embree.py's Harness class speaks it):
 *   in   u32 kind (1 triangles, 2 spheres), u64 a, u64 b
 *        triangles: a vertices of 3 f32, then b triangles of 3 u32 (0-based)
 *        spheres:   a spheres of 4 f32 (centre x, y, z, radius); b = 0
 *   out  f64 build_s (rtcCommitScene alone), f64 embree_mb (the growth of VmRSS across the
 *        geometry's buffers and the build), f64 version (RTC_VERSION, e.g. 31305)
 *   then any number of batches:
 *   in   u32 op (1 intersect, 2 occluded, 0 end), u64 n, n rays of 7 f32 (origin, direction,
 *        tfar); tnear is 0: embree.py has already moved each origin off its surface
 *   out  intersect: f64 seconds, then n i32 primID (-1: no hit) and n f32 tfar
 *        occluded:  f64 seconds, then n u8 (1: something lies in [0, tfar])
 *        end:       f64 peak_mb (this process's VmHWM), and the program exits
 * The seconds time the queries alone (rtcIntersect1 / rtcOccluded1, one ray at a time, the way
 * whitted traces), not the reading of the batch nor the writing of the answers.
 *
 * Build (embree.py does it, into /tmp): cc -O2 -o embree_harness embree_harness.c -lembree3
 */
#include <embree3/rtcore.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

enum { KIND_TRIANGLES = 1, KIND_SPHERES = 2 };
enum { OP_END = 0, OP_INTERSECT = 1, OP_OCCLUDED = 2 };
/* Floats a ray takes in a batch: origin (3), direction (3), tfar (1). */
enum { RAY_FLOATS = 7 };

static void die(const char *what) {
    fprintf(stderr, "embree_harness: %s\n", what);
    exit(1);
}

static void read_all(void *dst, size_t bytes) {
    if (bytes && fread(dst, 1, bytes, stdin) != bytes) die("short read on stdin");
}

static void write_all(const void *src, size_t bytes) {
    if (bytes && fwrite(src, 1, bytes, stdout) != bytes) die("short write on stdout");
}

static void *alloc(size_t bytes) {
    void *p = malloc(bytes ? bytes : 1);
    if (!p) die("out of memory");
    return p;
}

static double now(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* A field of /proc/self/status in kB, as MB: VmRSS (resident now) or VmHWM (the peak since exec;
 * ru_maxrss would also count the memory of the Python process that started this one). */
static double status_mb(const char *field) {
    FILE *fh = fopen("/proc/self/status", "r");
    char line[256];
    size_t len = strlen(field);
    double mb = 0.0;
    if (!fh) return 0.0;
    while (fgets(line, sizeof line, fh))
        if (strncmp(line, field, len) == 0 && line[len] == ':') mb = atof(line + len + 1) / 1024.0;
    fclose(fh);
    return mb;
}

static void on_error(void *user, enum RTCError code, const char *msg) {
    (void)user;
    fprintf(stderr, "embree_harness: Embree error %d: %s\n", (int)code, msg ? msg : "");
    exit(1);
}

static RTCGeometry triangles(RTCDevice dev, uint64_t nv, uint64_t nt) {
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv);
    unsigned *f = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), nt);
    read_all(v, nv * 3 * sizeof(float));
    read_all(f, nt * 3 * sizeof(unsigned));
    for (uint64_t k = 0; k < 3 * nt; k++)
        if (f[k] >= nv) die("a triangle's vertex index is out of range");
    return g;
}

static RTCGeometry spheres(RTCDevice dev, uint64_t n) {
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    float *v = rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), n);
    read_all(v, n * 4 * sizeof(float));
    return g;
}

static void serve(RTCScene scene) {
    struct RTCIntersectContext ctx;
    for (;;) {
        uint32_t op;
        uint64_t n;
        read_all(&op, sizeof op);
        if (op == OP_END) return;
        read_all(&n, sizeof n);
        float *rays = alloc(n * RAY_FLOATS * sizeof(float));
        read_all(rays, n * RAY_FLOATS * sizeof(float));
        if (op == OP_INTERSECT) {
            int32_t *prim = alloc(n * sizeof(int32_t));
            float *tfar = alloc(n * sizeof(float));
            double t0 = now();
            for (uint64_t k = 0; k < n; k++) {
                const float *r = rays + k * RAY_FLOATS;
                struct RTCRayHit rh;
                rh.ray.org_x = r[0], rh.ray.org_y = r[1], rh.ray.org_z = r[2];
                rh.ray.dir_x = r[3], rh.ray.dir_y = r[4], rh.ray.dir_z = r[5];
                rh.ray.tnear = 0.0f, rh.ray.tfar = r[6], rh.ray.time = 0.0f;
                rh.ray.mask = 0xFFFFFFFFu, rh.ray.id = 0, rh.ray.flags = 0;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
                rtcInitIntersectContext(&ctx);
                rtcIntersect1(scene, &ctx, &rh);
                prim[k] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? -1 : (int32_t)rh.hit.primID;
                tfar[k] = rh.ray.tfar;
            }
            double seconds = now() - t0;
            write_all(&seconds, sizeof seconds);
            write_all(prim, n * sizeof(int32_t));
            write_all(tfar, n * sizeof(float));
            free(prim);
            free(tfar);
        } else if (op == OP_OCCLUDED) {
            uint8_t *hit = alloc(n);
            double t0 = now();
            for (uint64_t k = 0; k < n; k++) {
                const float *r = rays + k * RAY_FLOATS;
                struct RTCRay ray;
                ray.org_x = r[0], ray.org_y = r[1], ray.org_z = r[2];
                ray.dir_x = r[3], ray.dir_y = r[4], ray.dir_z = r[5];
                ray.tnear = 0.0f, ray.tfar = r[6], ray.time = 0.0f;
                ray.mask = 0xFFFFFFFFu, ray.id = 0, ray.flags = 0;
                rtcInitIntersectContext(&ctx);
                rtcOccluded1(scene, &ctx, &ray);
                /* rtcOccluded1 sets tfar to −inf when it finds an occluder. */
                hit[k] = ray.tfar < 0.0f;
            }
            double seconds = now() - t0;
            write_all(&seconds, sizeof seconds);
            write_all(hit, n);
            free(hit);
        } else {
            die("unknown operation");
        }
        free(rays);
        fflush(stdout);
    }
}

int main(void) {
    uint32_t kind;
    uint64_t a, b;
    read_all(&kind, sizeof kind);
    read_all(&a, sizeof a);
    read_all(&b, sizeof b);
    /* One thread, as whitted's `render --threads 1` (embree.py also pins the process to one CPU). */
    RTCDevice dev = rtcNewDevice("threads=1");
    if (!dev) die("rtcNewDevice failed");
    rtcSetDeviceErrorFunction(dev, on_error, NULL);
    if (kind == KIND_SPHERES && !rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_POINT_GEOMETRY_SUPPORTED))
        die("this Embree was built without point geometry (spheres)");
    double rss_before = status_mb("VmRSS");
    RTCScene scene = rtcNewScene(dev);
    RTCGeometry g = kind == KIND_TRIANGLES ? triangles(dev, a, b)
                    : kind == KIND_SPHERES  ? spheres(dev, a)
                                            : (die("unknown geometry kind"), (RTCGeometry)0);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    double t0 = now();
    rtcCommitScene(scene);
    double build_s = now() - t0;
    double embree_mb = status_mb("VmRSS") - rss_before;
    double version = (double)rtcGetDeviceProperty(dev, RTC_DEVICE_PROPERTY_VERSION);
    write_all(&build_s, sizeof build_s);
    write_all(&embree_mb, sizeof embree_mb);
    write_all(&version, sizeof version);
    fflush(stdout);
    serve(scene);
    double peak_mb = status_mb("VmHWM");
    write_all(&peak_mb, sizeof peak_mb);
    fflush(stdout);
    rtcReleaseScene(scene);
    rtcReleaseDevice(dev);
    return 0;
}
