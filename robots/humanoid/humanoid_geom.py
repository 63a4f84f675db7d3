"""Conservative proximity of the humanoid's links, with which generate.py finds the
link pairs that touch at the zero pose (the SRDF's "Default" pairs) and the pelvis
height that stands the humanoid on the floor.

Proximity is tested on axis-aligned boxes: two meshes are `apart by margin m` when every
pair of their triangles has bounding boxes separated by at least m along some axis
(so their Euclidean distance is at least m). This is conservative: it may call close
meshes that are a little farther apart than m, never the reverse.
"""

import math

import meshlib as ml


def tri_boxes(verts, tris):
    out = []
    for a, b, c in tris:
        pa, pb, pc = verts[a], verts[b], verts[c]
        out.append((min(pa[0], pb[0], pc[0]), min(pa[1], pb[1], pc[1]), min(pa[2], pb[2], pc[2]),
                    max(pa[0], pb[0], pc[0]), max(pa[1], pb[1], pc[1]), max(pa[2], pb[2], pc[2])))
    return out


def box_of(points):
    lo, hi = ml.point_bounds(points)
    return (lo[0], lo[1], lo[2], hi[0], hi[1], hi[2])


def merge_boxes(boxes):
    return (min(b[0] for b in boxes), min(b[1] for b in boxes), min(b[2] for b in boxes),
            max(b[3] for b in boxes), max(b[4] for b in boxes), max(b[5] for b in boxes))


def boxes_close(a, b, margin):
    """True when the boxes are nearer than margin along every axis (i.e. not certified
    apart by margin)."""
    return (a[0] < b[3] + margin and b[0] < a[3] + margin and a[1] < b[4] + margin
            and b[1] < a[4] + margin and a[2] < b[5] + margin and b[2] < a[5] + margin)


def box_gap(a, b):
    """Largest axis separation between two boxes (negative: overlapping on all axes)."""
    return max(b[0] - a[3], a[0] - b[3], b[1] - a[4], a[1] - b[4], b[2] - a[5], a[2] - b[5])


def sets_close(A, B, margin, cell=0.04):
    """Triangle-box lists A and B: the smallest axis gap found among close pairs, or None
    when every pair is certified apart by margin."""
    if not A or not B:
        return None
    bA, bB = merge_boxes(A), merge_boxes(B)
    if not boxes_close(bA, bB, margin):
        return None
    A = [a for a in A if boxes_close(a, bB, margin)]
    B = [b for b in B if boxes_close(b, bA, margin)]
    if not A or not B:
        return None
    grid = {}
    for k, b in enumerate(B):
        for i in range(int(math.floor(b[0] / cell)), int(math.floor(b[3] / cell)) + 1):
            for j in range(int(math.floor(b[1] / cell)), int(math.floor(b[4] / cell)) + 1):
                for l in range(int(math.floor(b[2] / cell)), int(math.floor(b[5] / cell)) + 1):
                    grid.setdefault((i, j, l), []).append(k)
    worst = None
    for a in A:
        seen = set()
        for i in range(int(math.floor((a[0] - margin) / cell)), int(math.floor((a[3] + margin) / cell)) + 1):
            for j in range(int(math.floor((a[1] - margin) / cell)), int(math.floor((a[4] + margin) / cell)) + 1):
                for l in range(int(math.floor((a[2] - margin) / cell)), int(math.floor((a[5] + margin) / cell)) + 1):
                    for k in grid.get((i, j, l), ()):
                        if k in seen:
                            continue
                        seen.add(k)
                        if boxes_close(a, B[k], margin):
                            g = box_gap(a, B[k])
                            if worst is None or g < worst:
                                worst = g
    return worst


class PosedRobot:
    """World-frame vertices and triangle boxes of every link at one configuration.

    Self-collision pairs are culled with world boxes, then refined in the frame of the
    first link of the pair, so the verdict depends only on the links' relative pose
    (boxes of triangles are tight in a link's own frame, loose when rotated)."""

    def __init__(self, urdf, meshes, base_pose, q):
        """meshes: Urdf.collision_geometry(); q: {joint: value}."""
        self.poses = urdf.fk(base_pose, q)
        self.local, self.verts, self.boxes, self.link_box = {}, {}, {}, {}
        for link, items in meshes.items():
            lv, lt = [], []
            for origin, mesh in items:
                base = len(lv)
                lv.extend(ml.transform(origin, mesh.vertices))
                lt.extend((a + base, b + base, c + base) for a, b, c in mesh.triangles)
            self.local[link] = (lv, lt)
            w = ml.transform(self.poses[link], lv)
            self.verts[link], self.boxes[link] = w, tri_boxes(w, lt)
            self.link_box[link] = box_of(w)

    def relative(self, a, b):
        """Pose of link b in the frame of link a."""
        return ml.compose(ml.inverse(self.poses[a]), self.poses[b])

    def self_close_pairs(self, pairs, margin):
        out = []
        for a, b in pairs:
            if a not in self.boxes or b not in self.boxes:
                continue
            if not boxes_close(self.link_box[a], self.link_box[b], margin):
                continue
            la, ta = self.local[a]
            lb, tb = self.local[b]
            g = sets_close(tri_boxes(la, ta), tri_boxes(ml.transform(self.relative(a, b), lb), tb),
                           margin)
            if g is not None:
                out.append((a, b, g))
        return out
