//! Shards: `--shard I/N` read and checked, and the deterministic share of a suite's
//! scenes it selects. The unit is a scene with all its variants, because a variant's
//! speed-up is only meaningful against the baseline timed in the same process.

use results::Shard;

/// Most shards a suite may be split into.
pub const MAX_SHARDS: u32 = 1000;

/// Reads `I/N` (1 <= I <= N <= [`MAX_SHARDS`]); the error is one line for the user.
pub fn parse_shard(text: &str) -> Result<Shard, String> {
    let form = || format!("'{text}' is not a shard I/N (1 <= I <= N <= {MAX_SHARDS}, e.g. 1/4)");
    let (index, count) = text.trim().split_once('/').ok_or_else(form)?;
    let index: u32 = index.trim().parse().map_err(|_| form())?;
    let count: u32 = count.trim().parse().map_err(|_| form())?;
    if !(1..=MAX_SHARDS).contains(&count) {
        return Err(format!(
            "shard '{text}': the count must be 1 to {MAX_SHARDS}"
        ));
    }
    if !(1..=count).contains(&index) {
        return Err(format!("shard '{text}': the index must be 1 to {count}"));
    }
    Ok(Shard { index, count })
}

/// The items at the 0-based positions `p` with `p % N == I - 1`, in their order.
pub fn select<T>(items: Vec<T>, shard: Shard) -> Vec<T> {
    items
        .into_iter()
        .enumerate()
        .filter(|&(p, _)| shard.holds(p))
        .map(|(_, item)| item)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shard(index: u32, count: u32) -> Shard {
        Shard { index, count }
    }

    #[test]
    fn shards_take_every_nth_scene_and_together_take_each_once() {
        let scenes: Vec<usize> = (0..8).collect();
        assert_eq!(select(scenes.clone(), shard(1, 3)), vec![0, 3, 6]);
        assert_eq!(select(scenes.clone(), shard(2, 3)), vec![1, 4, 7]);
        assert_eq!(select(scenes.clone(), shard(3, 3)), vec![2, 5]);
        assert_eq!(select(scenes.clone(), shard(1, 1)), scenes);
        // More shards than scenes: the last ones are empty.
        assert_eq!(select(vec![0, 1], shard(3, 3)), Vec::<usize>::new());
        // Every scene lands in exactly one shard, at the position `Shard::position` says.
        for n in 1..=5u32 {
            let mut seen = vec![0; scenes.len()];
            for i in 1..=n {
                for (j, &p) in select(scenes.clone(), shard(i, n)).iter().enumerate() {
                    seen[p] += 1;
                    assert_eq!(shard(i, n).position(j), p);
                }
            }
            assert!(seen.iter().all(|&c| c == 1), "N = {n}: {seen:?}");
        }
    }

    #[test]
    fn shard_text_is_checked() {
        assert_eq!(parse_shard("1/2"), Ok(shard(1, 2)));
        assert_eq!(parse_shard("1000/1000"), Ok(shard(1000, 1000)));
        assert_eq!(parse_shard(" 3 / 4 "), Ok(shard(3, 4)));
        assert_eq!(
            parse_shard("0/2").unwrap_err(),
            "shard '0/2': the index must be 1 to 2"
        );
        assert_eq!(
            parse_shard("3/2").unwrap_err(),
            "shard '3/2': the index must be 1 to 2"
        );
        assert_eq!(
            parse_shard("1/1001").unwrap_err(),
            "shard '1/1001': the count must be 1 to 1000"
        );
        assert_eq!(
            parse_shard("1/0").unwrap_err(),
            "shard '1/0': the count must be 1 to 1000"
        );
        for bad in ["x", "1", "1/", "/2", "a/b", "-1/2", "1/2/3"] {
            assert!(
                parse_shard(bad).unwrap_err().contains("is not a shard I/N"),
                "{bad}"
            );
        }
    }
}
