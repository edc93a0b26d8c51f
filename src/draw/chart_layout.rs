//! A layered (Sugiyama-style) layout of a chart, top-down.
//!
//! 1. The chart is a bipartite graph: step → transition (the transition's
//!    preceding steps), transition → step (its following steps).
//! 2. **Back edges**: a depth-first search from the initial steps (then from
//!    any step not reached, in declaration order) marks the edges that go
//!    back to a node on the search path; they close the loops and are not
//!    used for layering. They are drawn on the left side, each in its own
//!    vertical lane, with an upward arrow (the GRAFCET convention for a
//!    link that goes up).
//! 3. **Layering**: longest path from the sources over the other edges, so
//!    every node sits below all its predecessors; steps take even layers
//!    and transitions odd ones, so rows alternate step / transition.
//! 4. Edges spanning several layers get one invisible *dummy* node per layer
//!    crossed, so the line keeps its own column and never crosses a box.
//! 5. **Ordering**: the first order is the search's discovery order; then
//!    alternate downward and upward barycentre sweeps (eight), keeping the
//!    order with the fewest edge crossings seen.
//! 6. **Coordinates**: each layer is packed in its order (a node's extents
//!    plus a gap apart), then four rounds of downward and upward sweeps pull
//!    every node to the mean x of its neighbours in the layer above (below),
//!    the pushes between neighbours shared both ways: a chain is a straight
//!    line, branches sit symmetrically under their divergence, a long link
//!    keeps its column. Each row is as tall as its tallest node.

/// Width and height of a node as the picture draws it: `left` and `right`
/// are the extents from its flow line (boxes, bars, labels, action blocks).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NodeSize {
    /// Extent left of the flow line.
    pub left: f64,
    /// Extent right of the flow line.
    pub right: f64,
    /// Height.
    pub height: f64,
}

/// What a node of the layout stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeKind {
    /// Step `i` of the model.
    Step(usize),
    /// Transition `i` of the model.
    Transition(usize),
    /// A point a long edge passes through.
    Dummy,
}

/// A node with its place.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placed {
    /// What it is.
    pub kind: NodeKind,
    /// Its layer (row).
    pub layer: usize,
    /// X of its flow line.
    pub x: f64,
}

/// A row of the layout.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// Y of its top.
    pub top: f64,
    /// Its height.
    pub height: f64,
}

impl Row {
    /// Y of its bottom.
    pub fn bottom(&self) -> f64 {
        self.top + self.height
    }
}

/// An edge drawn upwards on the left, in lane x.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BackEdge {
    /// Node it leaves (lower).
    pub from: usize,
    /// Node it enters (upper).
    pub to: usize,
    /// X of its vertical lane.
    pub lane: f64,
}

/// The whole layout.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Steps first (model order), then transitions, then dummies.
    pub nodes: Vec<Placed>,
    /// Rows, top to bottom.
    pub rows: Vec<Row>,
    /// Edges between adjacent layers (long edges already split at dummies).
    pub segments: Vec<(usize, usize)>,
    /// Edges closing loops.
    pub back: Vec<BackEdge>,
    /// Size of the drawing.
    pub width: f64,
    /// Height of the drawing.
    pub height: f64,
}

/// Vertical gap between rows (edges jog inside it).
pub const GAP: f64 = 44.0;
/// Horizontal gap between columns.
const COLUMN_GAP: f64 = 28.0;
/// Distance between back-edge lanes.
const LANE_GAP: f64 = 14.0;
/// Margin around the drawing.
pub const MARGIN: f64 = 16.0;
/// Height kept for the title line.
const TITLE: f64 = 20.0;

/// The chart's graph: `steps` nodes then `trans.len()` transition nodes;
/// `trans` gives each transition's (from, to) step lists.
struct Graph {
    out: Vec<Vec<usize>>,
    steps: usize,
}

impl Graph {
    fn new(steps: usize, trans: &[(Vec<usize>, Vec<usize>)]) -> Graph {
        let mut out = vec![Vec::new(); steps + trans.len()];
        for (t, (from, to)) in trans.iter().enumerate() {
            let tn = steps + t;
            for &s in from {
                if !out[s].contains(&tn) {
                    out[s].push(tn);
                }
            }
            for &s in to {
                if !out[tn].contains(&s) {
                    out[tn].push(s);
                }
            }
        }
        Graph { out, steps }
    }

    fn is_step(&self, n: usize) -> bool {
        n < self.steps
    }
}

/// Depth-first search: discovery rank of every node and the back edges.
fn search(g: &Graph, roots: &[usize]) -> (Vec<usize>, Vec<(usize, usize)>) {
    let n = g.out.len();
    let mut state = vec![0u8; n]; // 0 new, 1 on the path, 2 done
    let mut rank = vec![usize::MAX; n];
    let mut next_rank = 0;
    let mut back = Vec::new();
    let all: Vec<usize> = roots.iter().copied().chain(0..n).collect();
    for root in all {
        if state[root] != 0 {
            continue;
        }
        let mut stack = vec![(root, 0usize)];
        state[root] = 1;
        rank[root] = next_rank;
        next_rank += 1;
        while let Some(&mut (v, ref mut i)) = stack.last_mut() {
            if let Some(&w) = g.out[v].get(*i) {
                *i += 1;
                match state[w] {
                    0 => {
                        state[w] = 1;
                        rank[w] = next_rank;
                        next_rank += 1;
                        stack.push((w, 0));
                    }
                    1 => back.push((v, w)),
                    _ => {}
                }
            } else {
                state[v] = 2;
                stack.pop();
            }
        }
    }
    (rank, back)
}

/// Longest-path layers over the forward edges, steps even, transitions odd.
fn layers(g: &Graph, forward: &[(usize, usize)]) -> Vec<usize> {
    let n = g.out.len();
    let mut indegree = vec![0usize; n];
    let mut succ = vec![Vec::new(); n];
    for &(a, b) in forward {
        indegree[b] += 1;
        succ[a].push(b);
    }
    let mut layer: Vec<usize> = (0..n).map(|v| usize::from(!g.is_step(v))).collect();
    let mut ready: Vec<usize> = (0..n).filter(|&v| indegree[v] == 0).rev().collect();
    while let Some(v) = ready.pop() {
        let parity_ok = layer[v].is_multiple_of(2) == g.is_step(v);
        if !parity_ok {
            layer[v] += 1;
        }
        for &w in &succ[v] {
            layer[w] = layer[w].max(layer[v] + 1);
            indegree[w] -= 1;
            if indegree[w] == 0 {
                ready.push(w);
            }
        }
    }
    layer
}

/// Number of crossings between two adjacent layers.
fn crossings(pos: &[usize], segments: &[(usize, usize)], layer: &[usize], upper: usize) -> usize {
    let between: Vec<(usize, usize)> = segments
        .iter()
        .filter(|(a, _)| layer[*a] == upper)
        .map(|&(a, b)| (pos[a], pos[b]))
        .collect();
    let mut count = 0;
    for (i, &(a1, b1)) in between.iter().enumerate() {
        for &(a2, b2) in &between[i + 1..] {
            if (a1 < a2 && b1 > b2) || (a1 > a2 && b1 < b2) {
                count += 1;
            }
        }
    }
    count
}

fn total_crossings(order: &[Vec<usize>], segments: &[(usize, usize)], layer: &[usize]) -> usize {
    let pos = positions(order, layer.len());
    (0..order.len().saturating_sub(1))
        .map(|l| crossings(&pos, segments, layer, l))
        .sum()
}

fn positions(order: &[Vec<usize>], n: usize) -> Vec<usize> {
    let mut pos = vec![0; n];
    for row in order {
        for (i, &v) in row.iter().enumerate() {
            pos[v] = i;
        }
    }
    pos
}

/// One barycentre sweep; `down` orders each layer by its upper neighbours.
fn sweep(order: &mut [Vec<usize>], segments: &[(usize, usize)], n: usize, down: bool) {
    let layers: Vec<usize> = if down {
        (1..order.len()).collect()
    } else {
        (0..order.len().saturating_sub(1)).rev().collect()
    };
    for l in layers {
        let pos = positions(order, n);
        let mut keyed: Vec<(f64, usize, usize)> = order[l]
            .iter()
            .enumerate()
            .map(|(i, &v)| {
                let near: Vec<usize> = segments
                    .iter()
                    .filter_map(|&(a, b)| {
                        if down && b == v {
                            Some(pos[a])
                        } else if !down && a == v {
                            Some(pos[b])
                        } else {
                            None
                        }
                    })
                    .collect();
                let bary = if near.is_empty() {
                    i as f64
                } else {
                    near.iter().sum::<usize>() as f64 / near.len() as f64
                };
                (bary, i, v)
            })
            .collect();
        keyed.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
        order[l] = keyed.into_iter().map(|(_, _, v)| v).collect();
    }
}

/// Lays out a chart of `steps` steps (initial ones in `initial`) and the
/// transitions `trans` (from, to), with the sizes of the steps then the
/// transitions in `sizes`.
pub fn layout(
    steps: usize,
    initial: &[usize],
    trans: &[(Vec<usize>, Vec<usize>)],
    sizes: &[NodeSize],
) -> Layout {
    let g = Graph::new(steps, trans);
    let (rank, back_pairs) = search(&g, initial);
    let mut forward = Vec::new();
    for (v, outs) in g.out.iter().enumerate() {
        for &w in outs {
            if !back_pairs.contains(&(v, w)) {
                forward.push((v, w));
            }
        }
    }
    let mut layer = layers(&g, &forward);
    let mut kinds: Vec<NodeKind> = (0..g.out.len())
        .map(|v| {
            if g.is_step(v) {
                NodeKind::Step(v)
            } else {
                NodeKind::Transition(v - steps)
            }
        })
        .collect();
    let mut rank: Vec<(usize, usize)> = rank.into_iter().map(|r| (r, 0)).collect();
    // Split long edges at dummies.
    let mut segments = Vec::new();
    for &(a, b) in &forward {
        let mut prev = a;
        for l in layer[a] + 1..layer[b] {
            let d = kinds.len();
            kinds.push(NodeKind::Dummy);
            layer.push(l);
            rank.push((rank[a].0, l));
            segments.push((prev, d));
            prev = d;
        }
        segments.push((prev, b));
    }
    let n = kinds.len();
    let depth = layer.iter().max().map_or(0, |m| m + 1);
    let mut order: Vec<Vec<usize>> = vec![Vec::new(); depth];
    let mut by_rank: Vec<usize> = (0..n).collect();
    by_rank.sort_by_key(|&v| (rank[v], v));
    for v in by_rank {
        order[layer[v]].push(v);
    }
    let mut best = order.clone();
    let mut best_count = total_crossings(&order, &segments, &layer);
    for i in 0..8 {
        if best_count == 0 {
            break;
        }
        sweep(&mut order, &segments, n, i % 2 == 0);
        let count = total_crossings(&order, &segments, &layer);
        if count < best_count {
            best_count = count;
            best = order.clone();
        }
    }
    place(kinds, layer, &best, segments, back_pairs, sizes)
}

/// Places the nodes of one layer in their order, each as near as it can
/// to its `wanted` x: left to right, each at its wanted x or just right of
/// its left neighbour (its extents plus a gap), then the whole layer shifted
/// by the mean distance still missing, so the pushes are shared both ways.
fn pack(row: &[usize], wanted: &[f64], sizes: &[NodeSize], x: &mut [f64]) {
    let mut prev: Option<usize> = None;
    for (i, &v) in row.iter().enumerate() {
        x[v] = match prev {
            Some(p) => wanted[i].max(x[p] + sizes[p].right + COLUMN_GAP + sizes[v].left),
            None => wanted[i],
        };
        prev = Some(v);
    }
    let shift =
        row.iter().zip(wanted).map(|(&v, w)| w - x[v]).sum::<f64>() / row.len().max(1) as f64;
    for &v in row {
        x[v] += shift;
    }
}

/// X of every node's flow line: packed layers, then four rounds of
/// downward and upward sweeps pulling each node to the mean x of its
/// neighbours in the layer above (below), so chains stay straight, branches
/// sit symmetrically under their divergence and long links keep a column.
fn columns(order: &[Vec<usize>], segments: &[(usize, usize)], sizes: &[NodeSize]) -> Vec<f64> {
    let mut x = vec![0.0; sizes.len()];
    for row in order {
        pack(row, &vec![0.0; row.len()], sizes, &mut x);
    }
    for _ in 0..4 {
        for down in [true, false] {
            let layers: Vec<usize> = if down {
                (1..order.len()).collect()
            } else {
                (0..order.len().saturating_sub(1)).rev().collect()
            };
            for l in layers {
                let wanted: Vec<f64> = order[l]
                    .iter()
                    .map(|&v| {
                        let near: Vec<f64> = segments
                            .iter()
                            .filter_map(|&(a, b)| match (down, a == v, b == v) {
                                (true, _, true) => Some(x[a]),
                                (false, true, _) => Some(x[b]),
                                _ => None,
                            })
                            .collect();
                        if near.is_empty() {
                            x[v]
                        } else {
                            near.iter().sum::<f64>() / near.len() as f64
                        }
                    })
                    .collect();
                pack(&order[l], &wanted, sizes, &mut x);
            }
        }
    }
    x
}

/// Coordinates from the layers and the order.
fn place(
    kinds: Vec<NodeKind>,
    layer: Vec<usize>,
    order: &[Vec<usize>],
    segments: Vec<(usize, usize)>,
    back_pairs: Vec<(usize, usize)>,
    sizes: &[NodeSize],
) -> Layout {
    let size = |v: usize| match kinds[v] {
        NodeKind::Dummy => NodeSize {
            left: 0.0,
            right: 0.0,
            height: 0.0,
        },
        _ => sizes.get(v).copied().unwrap_or(NodeSize {
            left: 10.0,
            right: 10.0,
            height: 10.0,
        }),
    };
    let sizes_all: Vec<NodeSize> = (0..kinds.len()).map(size).collect();
    let x = columns(order, &segments, &sizes_all);
    let mut rows = Vec::new();
    // Room above the first row for a title and for back edges entering it.
    let mut top = MARGIN + TITLE + GAP;
    for row in order {
        let height = row.iter().map(|&v| size(v).height).fold(8.0, f64::max);
        rows.push(Row { top, height });
        top += height + GAP;
    }
    let height = top - GAP + MARGIN + GAP / 2.0;
    let left = (0..kinds.len())
        .map(|v| x[v] - size(v).left)
        .fold(0.0, f64::min);
    let right = (0..kinds.len())
        .map(|v| x[v] + size(v).right)
        .fold(0.0, f64::max);
    let lanes = back_pairs.len() as f64;
    // Short loops take the inner lanes, so lanes cross each other less.
    let mut back_pairs = back_pairs;
    back_pairs.sort_by_key(|&(from, to)| (layer[from].abs_diff(layer[to]), from, to));
    let shift = MARGIN + lanes * LANE_GAP + LANE_GAP - left;
    let back = back_pairs
        .iter()
        .enumerate()
        .map(|(k, &(from, to))| BackEdge {
            from,
            to,
            lane: MARGIN + (lanes - k as f64) * LANE_GAP - LANE_GAP / 2.0,
        })
        .collect();
    let nodes = kinds
        .iter()
        .enumerate()
        .map(|(v, &kind)| Placed {
            kind,
            layer: layer[v],
            x: x[v] + shift,
        })
        .collect();
    Layout {
        nodes,
        rows,
        segments,
        back,
        width: right + shift + MARGIN,
        height,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> NodeSize {
        NodeSize {
            left: 20.0,
            right: 20.0,
            height: 20.0,
        }
    }

    #[test]
    fn a_loop_is_layered_top_down_with_one_back_edge() {
        // S0 -T0-> S1 -T1-> S0
        let trans = vec![(vec![0], vec![1]), (vec![1], vec![0])];
        let l = layout(2, &[0], &trans, &[unit(); 4]);
        let layers: Vec<usize> = l.nodes.iter().map(|n| n.layer).collect();
        assert_eq!(layers, vec![0, 2, 1, 3]);
        assert_eq!(l.back.len(), 1);
        assert_eq!((l.back[0].from, l.back[0].to), (3, 0));
        assert!(l.back[0].lane < l.nodes[0].x - 20.0);
    }

    #[test]
    fn random_charts_keep_the_layout_invariants() {
        // A small linear congruential generator: reproducible charts.
        let mut seed: u64 = 0x2545_F491_4F6C_DD1D;
        let mut next = |bound: usize| {
            seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((seed >> 33) as usize) % bound
        };
        for _ in 0..300 {
            let steps = 1 + next(9);
            let mut trans = Vec::new();
            for _ in 0..next(12) {
                let from: Vec<usize> = (0..1 + next(2)).map(|_| next(steps)).collect();
                let to: Vec<usize> = (0..1 + next(3)).map(|_| next(steps)).collect();
                trans.push((from, to));
            }
            let initial = [next(steps)];
            let sizes = vec![unit(); steps + trans.len()];
            let l = layout(steps, &initial, &trans, &sizes);
            for (v, n) in l.nodes.iter().enumerate() {
                match n.kind {
                    NodeKind::Step(i) => assert!(i == v && n.layer % 2 == 0),
                    NodeKind::Transition(i) => assert!(i + steps == v && n.layer % 2 == 1),
                    NodeKind::Dummy => assert!(v >= steps + trans.len()),
                }
                assert!(n.x.is_finite() && n.x > 0.0 && n.x < l.width);
            }
            for &(a, b) in &l.segments {
                assert_eq!(l.nodes[a].layer + 1, l.nodes[b].layer);
            }
            for b in &l.back {
                assert!(l.nodes[b.to].layer <= l.nodes[b.from].layer);
                assert!(l.nodes.iter().all(|n| b.lane < n.x - 20.0));
            }
            // Nodes of one layer never share a column.
            for layer in 0..l.rows.len() {
                let mut xs: Vec<f64> = l
                    .nodes
                    .iter()
                    .filter(|n| n.layer == layer)
                    .map(|n| n.x)
                    .collect();
                xs.sort_by(f64::total_cmp);
                assert!(xs.windows(2).all(|w| w[1] - w[0] >= COLUMN_GAP - 1e-9));
            }
        }
    }

    #[test]
    fn branches_sit_side_by_side_and_long_edges_get_dummies() {
        // S0 -T0-> (S1, S2) simultaneous; S1 -T1-> S3; (S3, S2) -T2-> S0
        let trans = vec![
            (vec![0], vec![1, 2]),
            (vec![1], vec![3]),
            (vec![3, 2], vec![0]),
        ];
        let l = layout(4, &[0], &trans, &[unit(); 7]);
        assert_eq!(l.nodes[1].layer, l.nodes[2].layer);
        assert_ne!(l.nodes[1].x, l.nodes[2].x);
        assert!(l.nodes.iter().any(|n| n.kind == NodeKind::Dummy));
        for &(a, b) in &l.segments {
            assert_eq!(l.nodes[a].layer + 1, l.nodes[b].layer);
        }
    }
}
