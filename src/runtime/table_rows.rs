//! The rows of a table trace, kept until the run ends because the column
//! widths depend on every row: in memory up to a limit (4 MiB of cell
//! text), then moved to a temporary file, so that a long run's table does
//! not grow the process. The file holds each cell as its length (8 bytes,
//! little-endian) and its bytes, so any text round-trips; it is removed
//! when the rows are dropped.

use std::fs::{File, OpenOptions};
use std::io::{self, BufReader, BufWriter, Read, Write};
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};

/// Cell text kept in memory before the rows move to a file.
const MEMORY_LIMIT: usize = 4 << 20;

/// The rows of a table, `columns` cells each.
pub(crate) struct TableRows {
    columns: usize,
    limit: usize,
    /// The cells in memory: their texts end to end, and where each ends.
    text: String,
    ends: Vec<usize>,
    /// The rows moved out so far (they come before those in memory).
    spill: Option<Spill>,
}

/// A temporary file of rows.
struct Spill {
    path: PathBuf,
    out: BufWriter<File>,
}

impl Drop for Spill {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

impl TableRows {
    /// Rows of `columns` cells.
    pub(crate) fn new(columns: usize) -> Self {
        TableRows::with_limit(columns, MEMORY_LIMIT)
    }

    /// Rows that move to a file once their text passes `limit` bytes.
    pub(crate) fn with_limit(columns: usize, limit: usize) -> Self {
        TableRows {
            columns: columns.max(1),
            limit,
            text: String::new(),
            ends: Vec::new(),
            spill: None,
        }
    }

    /// Adds a cell to the row under way.
    pub(crate) fn push(&mut self, cell: &str) {
        self.text.push_str(cell);
        self.ends.push(self.text.len());
    }

    /// Ends the row under way (after `columns` cells); moves the rows to
    /// the file when memory holds too much.
    pub(crate) fn end_row(&mut self) -> io::Result<()> {
        if self.text.len() <= self.limit {
            return Ok(());
        }
        self.move_out()
    }

    #[cold]
    fn move_out(&mut self) -> io::Result<()> {
        if self.spill.is_none() {
            self.spill = Some(create_spill()?);
        }
        let Some(spill) = &mut self.spill else {
            return Ok(());
        };
        let mut start = 0;
        for &end in &self.ends {
            let cell = self.text.get(start..end).unwrap_or("").as_bytes();
            spill.out.write_all(&(cell.len() as u64).to_le_bytes())?;
            spill.out.write_all(cell)?;
            start = end;
        }
        self.text.clear();
        self.ends.clear();
        Ok(())
    }

    /// Calls `f` with each row's cells, in order.
    pub(crate) fn for_each_row(
        &mut self,
        mut f: impl FnMut(&mut dyn Iterator<Item = &str>) -> io::Result<()>,
    ) -> io::Result<()> {
        if let Some(spill) = &mut self.spill {
            spill.out.flush()?;
            let mut input = BufReader::new(File::open(&spill.path)?);
            let mut row: Vec<String> = vec![String::new(); self.columns];
            while read_row(&mut input, &mut row)? {
                f(&mut row.iter().map(String::as_str))?;
            }
        }
        let mut start = 0;
        for row in self.ends.chunks(self.columns) {
            let text = &self.text;
            let mut cells = row.iter().map(|&end| {
                let cell = text.get(start..end).unwrap_or("");
                start = end;
                cell
            });
            f(&mut cells)?;
        }
        Ok(())
    }
}

/// Reads one row of `row.len()` cells; false at the end of the file.
fn read_row(input: &mut impl Read, row: &mut [String]) -> io::Result<bool> {
    for (i, cell) in row.iter_mut().enumerate() {
        let mut len = [0u8; 8];
        match input.read_exact(&mut len) {
            Err(e) if i == 0 && e.kind() == io::ErrorKind::UnexpectedEof => return Ok(false),
            other => other?,
        }
        let len = usize::try_from(u64::from_le_bytes(len))
            .map_err(|_| io::Error::new(io::ErrorKind::InvalidData, "table cell too long"))?;
        let mut bytes = vec![0u8; len];
        input.read_exact(&mut bytes)?;
        *cell =
            String::from_utf8(bytes).map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))?;
    }
    Ok(true)
}

/// A new temporary file, named after the process and a counter.
fn create_spill() -> io::Result<Spill> {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let path = std::env::temp_dir().join(format!("plcrun-table-{}-{n}.rows", std::process::id()));
    let file = OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(true)
        .open(&path)?;
    Ok(Spill {
        path,
        out: BufWriter::new(file),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows_of(rows: &mut TableRows) -> Vec<Vec<String>> {
        let mut all = Vec::new();
        rows.for_each_row(|cells| {
            all.push(cells.map(str::to_string).collect());
            Ok(())
        })
        .unwrap();
        all
    }

    #[test]
    fn rows_come_back_in_order_from_memory_and_file() {
        let mut rows = TableRows::with_limit(3, 10);
        let mut expected = Vec::new();
        for k in 0..50 {
            let row = vec![k.to_string(), format!("T#{k}ms"), format!("'a\nb {k}'")];
            for cell in &row {
                rows.push(cell);
            }
            rows.end_row().unwrap();
            expected.push(row);
        }
        assert!(rows.spill.is_some());
        let path = rows.spill.as_ref().unwrap().path.clone();
        assert_eq!(rows_of(&mut rows), expected);
        drop(rows);
        assert!(!path.exists(), "the file is removed");
    }

    #[test]
    fn small_tables_stay_in_memory() {
        let mut rows = TableRows::new(2);
        rows.push("0");
        rows.push("T#0s");
        rows.end_row().unwrap();
        assert!(rows.spill.is_none());
        assert_eq!(rows_of(&mut rows), [["0", "T#0s"]]);
    }
}
