// The caustic photon map's estimate: the twin of `PhotonMap::irradiance`, `PhotonMap::gather`
// and `Nearest` in src/photon_map.rs. The photons are the CPU's map in its order: the implicit
// kd-tree whose node of the range `lo..hi` is its middle photon, splitting it along the axis
// stored with it into `lo..mid` and `mid + 1..hi`. The search keeps the `k` nearest photons in a
// max-heap, as the CPU's, and walks the tree as the CPU's recursion does, with a stack of the
// halves still to look at.

// `Photon`, with the axis its node splits.
struct Photon {
    position: vec3<f32>,
    axis: u32,
    power: vec3<f32>,
    pad0: u32,
    dir: vec3<f32>,
    pad1: u32,
}

// A photon found: its squared distance and its index.
struct Found {
    d2: f32,
    index: u32,
}

// `Nearest`: the photons found so far, as a max-heap on the squared distance, keeping at most
// `k`, and the squared radius beyond which no photon can join.
struct Nearest {
    heap: array<Found, MAX_GATHER>,
    len: u32,
    k: u32,
    max_d2: f32,
}

// `Nearest::offer`.
fn offer(nearest: ptr<function, Nearest>, d2: f32, index: u32) {
    if d2 >= (*nearest).max_d2 {
        return;
    }
    if (*nearest).len == (*nearest).k {
        // Replace the farthest, then let it sink to its place.
        (*nearest).heap[0] = Found(d2, index);
        var i = 0u;
        loop {
            var largest = i;
            for (var c = 2u * i + 1u; c <= 2u * i + 2u; c++) {
                if c < (*nearest).len && (*nearest).heap[c].d2 > (*nearest).heap[largest].d2 {
                    largest = c;
                }
            }
            if largest == i {
                break;
            }
            let swapped = (*nearest).heap[i];
            (*nearest).heap[i] = (*nearest).heap[largest];
            (*nearest).heap[largest] = swapped;
            i = largest;
        }
    } else {
        // Add at the end, then let it rise to its place.
        var i = (*nearest).len;
        (*nearest).heap[i] = Found(d2, index);
        (*nearest).len++;
        while i > 0u && (*nearest).heap[(i - 1u) / 2u].d2 < (*nearest).heap[i].d2 {
            let parent = (i - 1u) / 2u;
            let swapped = (*nearest).heap[i];
            (*nearest).heap[i] = (*nearest).heap[parent];
            (*nearest).heap[parent] = swapped;
            i = parent;
        }
    }
    if (*nearest).len == (*nearest).k {
        (*nearest).max_d2 = (*nearest).heap[0].d2;
    }
}

// A node whose nearer half is being searched: its middle photon and farther half come next.
// `offsets` are the distances from the point to the node's region along each axis, `distance2`
// the sum of their squares, `delta` the point's distance from the splitting plane.
struct Waiting {
    mid: u32,
    far_lo: u32,
    far_hi: u32,
    axis: u32,
    offsets: vec3<f32>,
    distance2: f32,
    delta: f32,
}

// `PhotonMap::gather` from the whole tree: offers `nearest` the photons near `point`, skipping
// the halves whose region lies farther away than its current radius. `outside` are the
// distances from the point to the photons' box along each axis, `distance2` the sum of their
// squares.
fn gather(point: vec3<f32>, outside: vec3<f32>, distance2: f32, nearest: ptr<function, Nearest>) {
    var stack: array<Waiting, PHOTON_STACK>;
    var size = 0u;
    var lo = 0u;
    var hi = frame.photon_count;
    var offsets = outside;
    var d2 = distance2;
    loop {
        // Down the nearer halves to a leaf.
        while hi - lo > PHOTON_LEAF_SIZE {
            let mid = (lo + hi) / 2u;
            let node = photons[mid];
            let delta = point[node.axis] - node.position[node.axis];
            var waiting = Waiting(mid, lo, mid, node.axis, offsets, d2, delta);
            if delta < 0.0 {
                waiting.far_lo = mid + 1u;
                waiting.far_hi = hi;
                hi = mid;
            } else {
                lo = mid + 1u;
            }
            stack[size] = waiting;
            size++;
        }
        for (var i = lo; i < hi; i++) {
            offer(nearest, dot(point - photons[i].position, point - photons[i].position), i);
        }
        // Back up: each waiting node's photon, then its farther half if it may hold nearer ones.
        var descended = false;
        while size > 0u && !descended {
            size--;
            let w = stack[size];
            let node = photons[w.mid].position;
            offer(nearest, dot(point - node, point - node), w.mid);
            // Across the splitting plane, the region is at least |delta| away along its axis.
            let far_d2 = w.distance2 - w.offsets[w.axis] * w.offsets[w.axis] + w.delta * w.delta;
            if far_d2 < (*nearest).max_d2 {
                offsets = w.offsets;
                offsets[w.axis] = abs(w.delta);
                d2 = far_d2;
                lo = w.far_lo;
                hi = w.far_hi;
                descended = true;
            }
        }
        if !descended {
            return;
        }
    }
}

// `PhotonMap::irradiance`: the irradiance at `point` on a surface whose normal (on the side the
// light is wanted from) is `normal`, from the `caustic_gather` photons nearest it within the
// map's largest radius: their power over the disc that holds them, each weighted by a cone
// filter; photons that arrived from behind the surface do not count.
fn caustic_irradiance(point: vec3<f32>, normal: vec3<f32>) -> vec3<f32> {
    let k = min(frame.caustic_gather, MAX_GATHER);
    if frame.photon_count == 0u || k == 0u {
        return vec3<f32>(0.0);
    }
    let radius2 = frame.photon_radius * frame.photon_radius;
    var nearest: Nearest;
    nearest.k = k;
    nearest.max_d2 = radius2;
    let outside = max(max(frame.photons_min - point, point - frame.photons_max), vec3<f32>(0.0));
    let distance2 = dot(outside, outside);
    if distance2 >= nearest.max_d2 {
        return vec3<f32>(0.0);
    }
    gather(point, outside, distance2, &nearest);
    var r2 = radius2;
    if nearest.len == k {
        r2 = nearest.max_d2;
    }
    if r2 <= 0.0 {
        return vec3<f32>(0.0);
    }
    let r = sqrt(r2);
    var sum = vec3<f32>(0.0);
    for (var i = 0u; i < nearest.len; i++) {
        let found = nearest.heap[i];
        let photon = photons[found.index];
        if dot(photon.dir, normal) < 0.0 {
            sum += photon.power * (1.0 - sqrt(found.d2) / r);
        }
    }
    // The cone filter keeps a third of the disc's weight: ∫(1 − d/r) dA = πr²/3.
    return sum / (PI * r2 / 3.0 * frame.photons_shot);
}
