//! Flood fill and connected-component labelling on boolean masks (iterative, no
//! recursion, so a 10-MP map cannot overflow the stack).

/// Neighbourhood used when growing a region.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Connectivity {
    Four,
    Eight,
}

fn neighbours(i: usize, w: usize, h: usize, conn: Connectivity, out: &mut [usize; 8]) -> usize {
    let (c, r) = ((i % w) as isize, (i / w) as isize);
    let mut n = 0;
    let four: [(isize, isize); 4] = [(1, 0), (-1, 0), (0, 1), (0, -1)];
    let diag: [(isize, isize); 4] = [(1, 1), (1, -1), (-1, 1), (-1, -1)];
    let extra: &[(isize, isize)] = if conn == Connectivity::Eight {
        &diag
    } else {
        &[]
    };
    for &(dc, dr) in four.iter().chain(extra) {
        let (nc, nr) = (c + dc, r + dr);
        if nc >= 0 && nr >= 0 && (nc as usize) < w && (nr as usize) < h {
            out[n] = nr as usize * w + nc as usize;
            n += 1;
        }
    }
    n
}

/// Cells reachable from `seeds` through cells where `passable` is true. Seeds that are
/// not passable are ignored.
pub fn flood_fill(
    passable: &[bool],
    width: usize,
    height: usize,
    seeds: &[usize],
    conn: Connectivity,
) -> Vec<bool> {
    assert_eq!(
        passable.len(),
        width * height,
        "mask size does not match width × height"
    );
    let mut reached = vec![false; passable.len()];
    let mut stack: Vec<usize> = Vec::new();
    for &s in seeds {
        if s < passable.len() && passable[s] && !reached[s] {
            reached[s] = true;
            stack.push(s);
        }
    }
    let mut nb = [0usize; 8];
    while let Some(i) = stack.pop() {
        let n = neighbours(i, width, height, conn, &mut nb);
        for &j in &nb[..n] {
            if passable[j] && !reached[j] {
                reached[j] = true;
                stack.push(j);
            }
        }
    }
    reached
}

/// Indices of the cells on the outer border of the grid.
pub fn border_cells(width: usize, height: usize) -> Vec<usize> {
    if width == 0 || height == 0 {
        return Vec::new();
    }
    let mut v: Vec<usize> = (0..width).collect();
    v.extend((0..width).map(|c| (height - 1) * width + c));
    v.extend((1..height.saturating_sub(1)).flat_map(|r| [r * width, r * width + width - 1]));
    v.sort_unstable();
    v.dedup();
    v
}

/// Labels of the connected components of `mask` (0 = not in mask, 1..=n components,
/// numbered in raster order of their first cell) and the size of each component.
pub fn label_components(
    mask: &[bool],
    width: usize,
    height: usize,
    conn: Connectivity,
) -> (Vec<u32>, Vec<usize>) {
    assert_eq!(
        mask.len(),
        width * height,
        "mask size does not match width × height"
    );
    let mut labels = vec![0u32; mask.len()];
    let mut sizes = Vec::new();
    let mut stack = Vec::new();
    let mut nb = [0usize; 8];
    for start in 0..mask.len() {
        if !mask[start] || labels[start] != 0 {
            continue;
        }
        let label = sizes.len() as u32 + 1;
        labels[start] = label;
        stack.push(start);
        let mut size = 0;
        while let Some(i) = stack.pop() {
            size += 1;
            let n = neighbours(i, width, height, conn, &mut nb);
            for &j in &nb[..n] {
                if mask[j] && labels[j] == 0 {
                    labels[j] = label;
                    stack.push(j);
                }
            }
        }
        sizes.push(size);
    }
    (labels, sizes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagonal_gap_blocks_four_but_not_eight() {
        // 1 0
        // 0 1
        let m = [true, false, false, true];
        assert_eq!(label_components(&m, 2, 2, Connectivity::Four).1, vec![1, 1]);
        assert_eq!(label_components(&m, 2, 2, Connectivity::Eight).1, vec![2]);
    }

    #[test]
    fn flood_stops_at_walls() {
        // a 5x3 grid with a wall column in the middle
        let w = 5;
        let pass: Vec<bool> = (0..15).map(|i| i % w != 2).collect();
        let r = flood_fill(&pass, w, 3, &[0], Connectivity::Four);
        assert_eq!(r.iter().filter(|&&x| x).count(), 6);
        assert!(!r[4]);
    }

    #[test]
    fn border_of_small_grids() {
        assert_eq!(border_cells(1, 1), vec![0]);
        assert_eq!(border_cells(3, 3).len(), 8);
        assert!(border_cells(0, 4).is_empty());
    }
}
