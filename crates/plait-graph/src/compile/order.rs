//! The dependency graph between passes (petgraph) and the execution order.
//!
//! Ordering rules, per resource R:
//! * every writer of R runs before every (other) reader of R;
//! * a "load-writer" of R (its slot has `loads = true`, or the pass also
//!   reads R) runs after every plain writer of R;
//! * all writers of R must then be totally ordered, else the result would
//!   depend on an arbitrary tie-break (`UnorderedWriters`).

use petgraph::graph::{DiGraph, NodeIndex};
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashSet};

use crate::error::{Error, ErrorKind};
use crate::load::Pipeline;
use crate::scene_resources::{DRAWN_HAIR, SCENE_RESOURCES, scene_resource};
use crate::schedule::{Binding, ResourceId, ScheduledPass};

/// `resource` is a declared index (`pipeline.resources`, then the scene's):
/// compile's bindings hold those until the schedule renumbers them.
pub(super) fn writes_to(pass: &ScheduledPass, resource: usize) -> Option<&Binding> {
    let id = Some(ResourceId::new(resource));
    pass.writes.iter().find(|b| b.resource == id)
}

fn reads_from(pass: &ScheduledPass, resource: usize) -> bool {
    let id = Some(ResourceId::new(resource));
    pass.reads.iter().any(|b| b.resource == id)
}

/// Scene resource ids (after the `declared` ones) a pass reads without naming
/// them: a hair draw reads the hair's vertices and indices.
pub(super) fn implicit_reads(pass: &ScheduledPass, declared: usize) -> Vec<usize> {
    if pass.draw != Some(crate::spec::Draw::Hair) {
        return Vec::new();
    }
    DRAWN_HAIR
        .iter()
        .filter_map(|name| scene_resource(name).map(|(i, _)| declared + i))
        .collect()
}

/// The name of resource id `resource`: declared, or a scene resource.
fn resource_name(pipeline: &Pipeline, resource: usize) -> String {
    match pipeline.resources.get_index(resource) {
        Some((name, _)) => name.clone(),
        None => SCENE_RESOURCES[resource - pipeline.resources.len()]
            .name
            .to_owned(),
    }
}

/// Builds the dependency graph and returns pass indices in execution order,
/// or `None` if it has a cycle. Reports never-written reads, cycles and
/// unordered writers.
pub(super) fn order_passes(
    passes: &[ScheduledPass],
    pipeline: &Pipeline,
    errors: &mut Vec<Error>,
) -> Option<Vec<usize>> {
    let (graph, nodes) = build_graph(passes, pipeline, errors);
    if report_cycles(&graph, passes, errors) {
        return None;
    }
    let reach = reachability(&graph, &nodes, passes.len());
    check_writers_ordered(passes, pipeline, &reach, errors);
    Some(execution_order(&graph, &nodes))
}

/// Whether pass `pass` reads `resource`, by name or implicitly.
fn reads_any(pass: &ScheduledPass, resource: usize, declared: usize) -> bool {
    reads_from(pass, resource) || implicit_reads(pass, declared).contains(&resource)
}

/// The passes that write `resource`, in file order.
fn writers_of(passes: &[ScheduledPass], resource: usize) -> Vec<usize> {
    (0..passes.len())
        .filter(|&p| writes_to(&passes[p], resource).is_some())
        .collect()
}

/// The dependency graph, one node per pass (weighted by its index), with the
/// ordering rules' edges; reports reads of resources nothing writes.
fn build_graph(
    passes: &[ScheduledPass],
    pipeline: &Pipeline,
    errors: &mut Vec<Error>,
) -> (DiGraph<usize, ()>, Vec<NodeIndex>) {
    let mut graph: DiGraph<usize, ()> = DiGraph::new();
    let nodes: Vec<NodeIndex> = (0..passes.len()).map(|i| graph.add_node(i)).collect();
    let mut add_edge = |from: usize, to: usize| {
        if from != to {
            graph.update_edge(nodes[from], nodes[to], ());
        }
    };

    let declared = pipeline.resources.len();
    let reads = |p: usize, resource: usize| reads_any(&passes[p], resource, declared);
    for resource in 0..declared + SCENE_RESOURCES.len() {
        let writers = writers_of(passes, resource);
        let readers: Vec<usize> = (0..passes.len()).filter(|&p| reads(p, resource)).collect();
        check_written(passes, pipeline, resource, &writers, &readers, errors);
        for &w in &writers {
            for &r in &readers {
                add_edge(w, r);
            }
        }
        let is_load_writer = |p: usize| {
            writes_to(&passes[p], resource).is_some_and(|b| b.loads) || reads(p, resource)
        };
        for &plain in writers.iter().filter(|&&w| !is_load_writer(w)) {
            for &load in writers.iter().filter(|&&w| is_load_writer(w)) {
                add_edge(plain, load);
            }
        }
    }
    (graph, nodes)
}

/// Reports each read of `resource` by `readers` when nothing writes it (or,
/// for an earlier frame's version, nothing writes the resource it is of).
fn check_written(
    passes: &[ScheduledPass],
    pipeline: &Pipeline,
    resource: usize,
    writers: &[usize],
    readers: &[usize],
    errors: &mut Vec<Error>,
) {
    // An earlier frame's version is written by the engine (a copy of the
    // resource after each frame): it needs a writer of the resource. The
    // scene writes its resources before any pass.
    let declared = pipeline.resources.len();
    let previous_of = pipeline
        .resources
        .get_index(resource)
        .and_then(|(_, r)| r.previous_of.as_ref());
    let written_by_someone = match previous_of {
        Some(of) => pipeline
            .resources
            .get_index_of(&of.resource)
            .is_some_and(|base| passes.iter().any(|p| writes_to(p, base).is_some())),
        None => !writers.is_empty() || resource >= declared,
    };
    if written_by_someone {
        return;
    }
    for &r in readers {
        for b in passes[r]
            .reads
            .iter()
            .filter(|b| b.resource == Some(ResourceId::new(resource)))
        {
            let kind = match previous_of {
                Some(of) => ErrorKind::HistoryNeverWritten {
                    previous: b.resource_name.clone(),
                    resource: of.resource.clone(),
                    reader: passes[r].name.clone(),
                },
                None => ErrorKind::NeverWritten {
                    resource: b.resource_name.clone(),
                    reader: passes[r].name.clone(),
                },
            };
            errors.push(Error::new(b.location.clone(), kind));
        }
    }
}

/// Reports one cycle per strongly connected component; whether there was any.
fn report_cycles(
    graph: &DiGraph<usize, ()>,
    passes: &[ScheduledPass],
    errors: &mut Vec<Error>,
) -> bool {
    let mut has_cycle = false;
    for scc in petgraph::algo::tarjan_scc(graph) {
        if scc.len() > 1 {
            has_cycle = true;
            let members: HashSet<NodeIndex> = scc.iter().copied().collect();
            let cycle = cycle_through(graph, &members);
            let first = cycle.iter().copied().min().unwrap_or(0);
            let names = cycle
                .iter()
                .chain(cycle.first())
                .map(|&i| passes[i].name.clone())
                .collect();
            errors.push(Error::new(
                passes[first].location.clone(),
                ErrorKind::Cycle(names),
            ));
        }
    }
    has_cycle
}

/// `reach[a][b]`: b runs after a along edges (or is a).
fn reachability(graph: &DiGraph<usize, ()>, nodes: &[NodeIndex], count: usize) -> Vec<Vec<bool>> {
    nodes
        .iter()
        .map(|&start| {
            let mut row = vec![false; count];
            let mut dfs = petgraph::visit::Dfs::new(graph, start);
            while let Some(n) = dfs.next(graph) {
                row[graph[n]] = true;
            }
            row
        })
        .collect()
}

/// Reports, per resource, the first pair of its writers the edges leave
/// unordered.
fn check_writers_ordered(
    passes: &[ScheduledPass],
    pipeline: &Pipeline,
    reach: &[Vec<bool>],
    errors: &mut Vec<Error>,
) {
    for resource in 0..pipeline.resources.len() + SCENE_RESOURCES.len() {
        let writers = writers_of(passes, resource);
        'pairs: for (i, &a) in writers.iter().enumerate() {
            for &b in &writers[i + 1..] {
                if !reach[a][b] && !reach[b][a] {
                    let location = writes_to(&passes[b], resource)
                        .map_or(passes[b].location.clone(), |x| x.location.clone());
                    errors.push(Error::new(
                        location,
                        ErrorKind::UnorderedWriters {
                            resource: resource_name(pipeline, resource),
                            first: passes[a].name.clone(),
                            second: passes[b].name.clone(),
                        },
                    ));
                    break 'pairs;
                }
            }
        }
    }
}

/// The execution order of an acyclic graph: Kahn's algorithm, among ready
/// passes the earliest in the file first.
fn execution_order(graph: &DiGraph<usize, ()>, nodes: &[NodeIndex]) -> Vec<usize> {
    let mut indegree: Vec<usize> = nodes
        .iter()
        .map(|&n| graph.neighbors_directed(n, petgraph::Incoming).count())
        .collect();
    let mut ready: BinaryHeap<Reverse<usize>> = (0..nodes.len())
        .filter(|&i| indegree[i] == 0)
        .map(Reverse)
        .collect();
    let mut order = Vec::with_capacity(nodes.len());
    while let Some(Reverse(p)) = ready.pop() {
        order.push(p);
        for next in graph.neighbors(nodes[p]) {
            let q = graph[next];
            indegree[q] -= 1;
            if indegree[q] == 0 {
                ready.push(Reverse(q));
            }
        }
    }
    order
}

/// One cycle inside a strongly connected component, as pass indices,
/// starting at its earliest pass in file order.
fn cycle_through(graph: &DiGraph<usize, ()>, members: &HashSet<NodeIndex>) -> Vec<usize> {
    let Some(&start) = members.iter().min_by_key(|n| graph[**n]) else {
        return Vec::new();
    };
    // Breadth-first search back to `start`, remembering parents.
    let mut parent: std::collections::HashMap<NodeIndex, NodeIndex> = Default::default();
    let mut queue = std::collections::VecDeque::from([start]);
    while let Some(n) = queue.pop_front() {
        let mut successors: Vec<NodeIndex> =
            graph.neighbors(n).filter(|s| members.contains(s)).collect();
        successors.sort_by_key(|s| graph[*s]);
        for s in successors {
            if s == start {
                let mut path = vec![graph[n]];
                let mut cur = n;
                while cur != start {
                    let Some(&p) = parent.get(&cur) else { break };
                    path.push(graph[p]);
                    cur = p;
                }
                path.reverse();
                return path;
            }
            if let std::collections::hash_map::Entry::Vacant(e) = parent.entry(s) {
                e.insert(n);
                queue.push_back(s);
            }
        }
    }
    vec![graph[start]]
}
