//! Wall segments indexed for queries: the uniform grid a beam walks with a DDA
//! ([`SegmentGrid::cast`]), nearest-wall distance ([`SegmentGrid::clearance`]), and the coarse
//! culling blocks of the segment scan ([`BlockIndex`]). The lowest layer of the lidar:
//! [`super::segment_scan`] and [`super::lidar`] both build on it, and it on neither.

/// Wall segments bucketed in a uniform grid.
#[derive(Debug, Clone)]
pub struct SegmentGrid {
    /// (ax, ay, bx - ax, by - ay) per segment.
    segs: Vec<[f64; 4]>,
    /// Bit i: segment i starts at the end point of segment i - 1 (same polyline).
    joined: Vec<u64>,
    /// Length of the longest segment.
    max_len: f64,
    /// Coarse blocks for the segment scan's culling by range and occlusion.
    blocks: BlockIndex,
    x0: f64,
    y0: f64,
    cell: f64,
    nx: usize,
    ny: usize,
    /// CSR: the segments of cell `c` are `items[start[c]..start[c + 1]]`, and
    /// `cell_segs` holds copies of them in the same order (contiguous for the cast loop).
    start: Vec<u32>,
    items: Vec<u32>,
    cell_segs: Vec<[f64; 4]>,
}

impl SegmentGrid {
    /// Grid over the edges of closed polylines (each closes back to its first point).
    pub fn new(walls: &[Vec<[f64; 2]>]) -> Self {
        let mut segs = Vec::new();
        let mut joined = Vec::new();
        for w in walls {
            let n = w.len();
            let m = if n == 2 { 1 } else { n };
            for i in 0..m {
                let (a, b) = (w[i], w[(i + 1) % n]);
                let k = segs.len();
                if k % 64 == 0 {
                    joined.push(0u64);
                }
                joined[k / 64] |= ((i > 0) as u64) << (k % 64);
                segs.push([a[0], a[1], b[0] - a[0], b[1] - a[1]]);
            }
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        let (mut total_len, mut max_len) = (0.0, 0.0f64);
        for s in &segs {
            for p in [[s[0], s[1]], [s[0] + s[2], s[1] + s[3]]] {
                for k in 0..2 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            total_len += s[2].hypot(s[3]);
            max_len = max_len.max(s[2].hypot(s[3]));
        }
        let mean = total_len / segs.len().max(1) as f64;
        let (w, h) = ((hi[0] - lo[0]).max(1e-3), (hi[1] - lo[1]).max(1e-3));
        // Cells about three mean segment lengths wide (a handful of segments where a
        // wall crosses; measured on berlin: 1x 114 us, 2x 84, 4x 80, 8x 98 us per scan in
        // a dev build), never so fine that the grid exceeds ~4 M cells.
        let mut cell = (3.0 * mean).clamp(0.1, 2.0);
        while (w / cell + 2.0) * (h / cell + 2.0) > 4.0e6 {
            cell *= 1.5;
        }
        let (x0, y0) = (lo[0] - cell, lo[1] - cell);
        let nx = (w / cell).ceil() as usize + 2;
        let ny = (h / cell).ceil() as usize + 2;
        let (start, items) = bucket_segments(&segs, [x0, y0], cell, [nx, ny]);
        let cell_segs = items.iter().map(|&k| segs[k as usize]).collect();
        let blocks = BlockIndex::new(&segs, lo, hi);
        SegmentGrid {
            segs,
            joined,
            max_len,
            blocks,
            x0,
            y0,
            cell,
            nx,
            ny,
            start,
            items,
            cell_segs,
        }
    }

    pub fn num_segments(&self) -> usize {
        self.segs.len()
    }

    /// All wall segments as (ax, ay, bx - ax, by - ay).
    pub fn segments(&self) -> &[[f64; 4]] {
        &self.segs
    }

    /// Whether segment `i` starts where segment `i - 1` ends (the next edge of the same
    /// polyline), so the two share that end point.
    #[inline(always)]
    pub(crate) fn continues_previous(&self, i: usize) -> bool {
        self.joined[i / 64] >> (i % 64) & 1 == 1
    }

    /// Length of the longest segment (0 without segments).
    pub(crate) fn max_len(&self) -> f64 {
        self.max_len
    }

    /// Bounding box of the segments: ([x lo, y lo], [x hi, y hi]).
    pub fn bounds(&self) -> ([f64; 2], [f64; 2]) {
        (
            [self.x0 + self.cell, self.y0 + self.cell],
            [
                self.x0 + (self.nx - 1) as f64 * self.cell,
                self.y0 + (self.ny - 1) as f64 * self.cell,
            ],
        )
    }

    /// The coarse culling blocks of the segment scan.
    pub fn blocks(&self) -> &BlockIndex {
        &self.blocks
    }

    /// True when no wall segment comes within `r` of `(x, y)`.
    pub fn clear_of(&self, x: f64, y: f64, r: f64) -> bool {
        self.nearest_within(x, y, r) >= r
    }

    /// Distance from `(x, y)` to the nearest wall segment (infinity without walls):
    /// searched in growing boxes of cells, so it costs what the neighbourhood holds.
    pub fn clearance(&self, x: f64, y: f64) -> f64 {
        let extent = (self.nx.max(self.ny) as f64 + 2.0) * self.cell;
        let far = (x - self.x0).abs().max((y - self.y0).abs()) + extent;
        let mut r = self.cell;
        loop {
            let d = self.nearest_within(x, y, r);
            if d <= r || r >= far {
                return d;
            }
            r *= 2.0;
        }
    }

    /// The smallest distance from `(x, y)` to the segments of the cells overlapping the
    /// box of half side `r` around it: exact when it is at most `r` (every segment
    /// within `r` is in those cells); a larger value only bounds the true distance.
    fn nearest_within(&self, x: f64, y: f64, r: f64) -> f64 {
        let inv = 1.0 / self.cell;
        let ix0 = ((x - r - self.x0) * inv).floor().max(0.0) as usize;
        let iy0 = ((y - r - self.y0) * inv).floor().max(0.0) as usize;
        let ix1 = (((x + r - self.x0) * inv).floor() as isize).min(self.nx as isize - 1);
        let iy1 = (((y + r - self.y0) * inv).floor() as isize).min(self.ny as isize - 1);
        let mut best = f64::INFINITY;
        if ix1 < 0 || iy1 < 0 || !(x.is_finite() && y.is_finite()) {
            return best;
        }
        for iy in iy0..=iy1 as usize {
            for ix in ix0..=ix1 as usize {
                let c = iy * self.nx + ix;
                for &k in &self.items[self.start[c] as usize..self.start[c + 1] as usize] {
                    let s = &self.segs[k as usize];
                    let l2 = s[2] * s[2] + s[3] * s[3];
                    let (wx, wy) = (x - s[0], y - s[1]);
                    let t = if l2 > 0.0 {
                        ((wx * s[2] + wy * s[3]) / l2).clamp(0.0, 1.0)
                    } else {
                        0.0
                    };
                    let (dx, dy) = (wx - t * s[2], wy - t * s[3]);
                    best = best.min(dx * dx + dy * dy);
                }
            }
        }
        best.sqrt()
    }

    /// Distance along the unit direction `(dx, dy)` from `(ox, oy)` to the first wall,
    /// or `f64::INFINITY` if none within `max_t`.
    pub fn cast(&self, ox: f64, oy: f64, dx: f64, dy: f64, max_t: f64) -> f64 {
        let (gx1, gy1) = (
            self.x0 + self.nx as f64 * self.cell,
            self.y0 + self.ny as f64 * self.cell,
        );
        // Clip the ray to the grid box (slab method).
        let (mut t0, mut t1) = (0.0f64, max_t);
        for (o, d, lo, hi) in [(ox, dx, self.x0, gx1), (oy, dy, self.y0, gy1)] {
            if d.abs() < 1e-300 {
                if o < lo || o > hi {
                    return f64::INFINITY;
                }
            } else {
                let (a, b) = ((lo - o) / d, (hi - o) / d);
                t0 = t0.max(a.min(b));
                t1 = t1.min(a.max(b));
            }
        }
        if t0 > t1 {
            return f64::INFINITY;
        }
        let inv = 1.0 / self.cell;
        let (px, py) = (ox + dx * t0, oy + dy * t0);
        let mut ix = (((px - self.x0) * inv).floor() as isize).clamp(0, self.nx as isize - 1);
        let mut iy = (((py - self.y0) * inv).floor() as isize).clamp(0, self.ny as isize - 1);
        let (sx, sy) = (if dx > 0.0 { 1 } else { -1 }, if dy > 0.0 { 1 } else { -1 });
        let next_x = |ix: isize| self.x0 + (ix + (sx > 0) as isize) as f64 * self.cell;
        let next_y = |iy: isize| self.y0 + (iy + (sy > 0) as isize) as f64 * self.cell;
        let mut tmx = if dx != 0.0 {
            (next_x(ix) - ox) / dx
        } else {
            f64::INFINITY
        };
        let mut tmy = if dy != 0.0 {
            (next_y(iy) - oy) / dy
        } else {
            f64::INFINITY
        };
        let (tdx, tdy) = (self.cell / dx.abs(), self.cell / dy.abs());
        let mut best = f64::INFINITY;
        loop {
            let c = iy as usize * self.nx + ix as usize;
            for sg in &self.cell_segs[self.start[c] as usize..self.start[c + 1] as usize] {
                best = best.min(ray_segment(ox, oy, dx, dy, sg));
            }
            let t_exit = tmx.min(tmy);
            if best <= t_exit || t_exit > t1 {
                break;
            }
            if tmx < tmy {
                ix += sx;
                tmx += tdx;
                if ix < 0 || ix >= self.nx as isize {
                    break;
                }
            } else {
                iy += sy;
                tmy += tdy;
                if iy < 0 || iy >= self.ny as isize {
                    break;
                }
            }
        }
        if best <= max_t {
            best
        } else {
            f64::INFINITY
        }
    }
}

/// Ray parameter t >= 0 where `o + t d` meets segment `s`, or infinity. Branch-free
/// (the hit conditions become a select), which matters: ray casting is ~75 % of a scan
/// and the hit/miss branches are unpredictable.
#[inline(always)]
pub(crate) fn ray_segment(ox: f64, oy: f64, dx: f64, dy: f64, s: &[f64; 4]) -> f64 {
    let (ex, ey) = (s[2], s[3]);
    let den = dx * ey - dy * ex;
    let (wx, wy) = (s[0] - ox, s[1] - oy);
    let sign = if den < 0.0 { -1.0 } else { 1.0 };
    let ad = den * sign;
    let tn = (wx * ey - wy * ex) * sign; // t * |den|
    let un = (wx * dy - wy * dx) * sign; // u * |den|
    let t = tn / ad;
    let ok = (ad > 1e-14) & (tn >= 0.0) & (un >= 0.0) & (un <= ad);
    if ok {
        t
    } else {
        f64::INFINITY
    }
}

/// Segments bucketed in the square cells (side `cell`, `n[0]` × `n[1]` from `origin`)
/// they touch, as CSR: cell `c` holds `items[start[c]..start[c + 1]]` (segment indices).
pub(crate) fn bucket_segments(
    segs: &[[f64; 4]],
    origin: [f64; 2],
    cell: f64,
    n: [usize; 2],
) -> (Vec<u32>, Vec<u32>) {
    let [nx, ny] = n;
    let index =
        |v: f64, v0: f64, n: usize| (((v - v0) / cell).floor().max(0.0) as usize).min(n - 1);
    let mut buckets: Vec<Vec<u32>> = vec![Vec::new(); nx * ny];
    for (k, s) in segs.iter().enumerate() {
        let (ax, ay, bx, by) = (s[0], s[1], s[0] + s[2], s[1] + s[3]);
        for iy in index(ay.min(by), origin[1], ny)..=index(ay.max(by), origin[1], ny) {
            for ix in index(ax.min(bx), origin[0], nx)..=index(ax.max(bx), origin[0], nx) {
                let (cx, cy) = (origin[0] + ix as f64 * cell, origin[1] + iy as f64 * cell);
                if segment_touches_box(s, cx, cy, cx + cell, cy + cell) {
                    buckets[iy * nx + ix].push(k as u32);
                }
            }
        }
    }
    let mut start = Vec::with_capacity(nx * ny + 1);
    let mut items = Vec::new();
    start.push(0);
    for b in buckets {
        items.extend(b);
        start.push(items.len() as u32);
    }
    (start, items)
}

/// Conservative segment–box overlap (bounding boxes plus separating line of the segment).
fn segment_touches_box(s: &[f64; 4], x0: f64, y0: f64, x1: f64, y1: f64) -> bool {
    let eps = 1e-9;
    let (ax, ay, ex, ey) = (s[0], s[1], s[2], s[3]);
    let side = |x: f64, y: f64| ex * (y - ay) - ey * (x - ax);
    let c = [side(x0, y0), side(x1, y0), side(x0, y1), side(x1, y1)];
    let scale = ex.hypot(ey) * (x1 - x0) * eps + eps;
    !(c.iter().all(|&v| v > scale) || c.iter().all(|&v| v < -scale))
}

/// Side of a culling block (m): coarse enough that the blocks within a 30 m range are a
/// few dozen, fine enough that a block hidden behind a near wall is skipped. Measured on
/// Spielberg (1081 beams, median over a lap, dev build, shared machine): 2 m 25 us,
/// 4 m 17.8, 8 m 16.1, 16 m 20.4 us per scan.
const BLOCK_SIZE: f64 = 8.0;

/// Wall segments bucketed in square blocks of [`BLOCK_SIZE`] (CSR, each segment listed
/// once in every block it touches).
#[derive(Debug, Clone)]
pub struct BlockIndex {
    x0: f64,
    y0: f64,
    size: f64,
    nx: usize,
    ny: usize,
    start: Vec<u32>,
    items: Vec<u32>,
}

impl BlockIndex {
    /// Blocks over segments `segs` ((ax, ay, ex, ey)) inside the box `lo`..`hi`.
    pub fn new(segs: &[[f64; 4]], lo: [f64; 2], hi: [f64; 2]) -> Self {
        let (w, h) = ((hi[0] - lo[0]).max(1e-3), (hi[1] - lo[1]).max(1e-3));
        let mut size = BLOCK_SIZE;
        while (w / size + 1.0) * (h / size + 1.0) > 1.0e6 {
            size *= 2.0;
        }
        let (x0, y0) = (lo[0], lo[1]);
        let nx = (w / size).floor() as usize + 1;
        let ny = (h / size).floor() as usize + 1;
        let (start, items) = bucket_segments(segs, [x0, y0], size, [nx, ny]);
        BlockIndex {
            x0,
            y0,
            size,
            nx,
            ny,
            start,
            items,
        }
    }

    /// Non-empty blocks whose box comes within `r` of `(ox, oy)`, as (distance to the
    /// box, block index), nearest first.
    pub(crate) fn near(&self, ox: f64, oy: f64, r: f64, out: &mut Vec<(f64, u32)>) {
        out.clear();
        let inv = 1.0 / self.size;
        let lo = |v: f64, v0: f64| ((v - r - v0) * inv).floor().max(0.0) as usize;
        let hi = |v: f64, v0: f64, n: usize| {
            let t = ((v + r - v0) * inv).floor();
            if t < 0.0 {
                None
            } else {
                Some((t as usize).min(n - 1))
            }
        };
        let (Some(ix1), Some(iy1)) = (hi(ox, self.x0, self.nx), hi(oy, self.y0, self.ny)) else {
            return;
        };
        for iy in lo(oy, self.y0)..=iy1 {
            let by = self.y0 + iy as f64 * self.size;
            let dy = (by - oy).max(oy - by - self.size).max(0.0);
            for ix in lo(ox, self.x0)..=ix1 {
                let b = iy * self.nx + ix;
                if self.start[b] == self.start[b + 1] {
                    continue;
                }
                let bx = self.x0 + ix as f64 * self.size;
                let dx = (bx - ox).max(ox - bx - self.size).max(0.0);
                let d = dx.hypot(dy);
                if d <= r {
                    out.push((d, b as u32));
                }
            }
        }
        out.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
    }

    pub(crate) fn corners(&self, b: usize) -> [[f64; 2]; 4] {
        let (ix, iy) = (b % self.nx, b / self.nx);
        let (x, y) = (
            self.x0 + ix as f64 * self.size,
            self.y0 + iy as f64 * self.size,
        );
        let s = self.size;
        [[x, y], [x + s, y], [x, y + s], [x + s, y + s]]
    }

    pub(crate) fn segments(&self, b: usize) -> &[u32] {
        &self.items[self.start[b] as usize..self.start[b + 1] as usize]
    }
}
