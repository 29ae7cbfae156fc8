//! Union-find over `u32` ids in a flat parent array, for the passes that group vertices or
//! triangles into components (closed parts, sheets, connected pieces).

/// The root of `x`'s set in `parent` (each entry its parent, a root its own), halving the
/// path on the way: near-constant time per call over a whole run.
pub fn root(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let up = parent[parent[x as usize] as usize];
        parent[x as usize] = up;
        x = up;
    }
    x
}

/// `n` sets of one: each id its own parent.
pub fn singletons(n: usize) -> Vec<u32> {
    (0..n as u32).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joined_sets_share_a_root_and_the_rest_keep_theirs() {
        let mut parent = singletons(6);
        for (a, b) in [(0, 1), (2, 3), (1, 3)] {
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            parent[rb as usize] = ra;
        }
        let r = root(&mut parent, 3);
        assert!([0, 1, 2].iter().all(|&x| root(&mut parent, x) == r));
        assert_eq!(root(&mut parent, 4), 4);
        assert_eq!(root(&mut parent, 5), 5);
    }
}
