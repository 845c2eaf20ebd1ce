//! A run's data in the store: the runs committed with their data (one transaction per group,
//! rows of `runs` and `run_data`), and each run's fields and error-estimate values read back,
//! checked against the study hash, from its `run_data` row or a legacy file, the damaged ones
//! named.

use super::*;

impl Store {
    /// An immediate write transaction on the store, once the directory is checked to hold this
    /// study still (no other writer between the check and the rows): `what` names the rows
    /// refused otherwise ("this run is", "this paired solve is").
    pub(super) fn checked_transaction(
        &self,
        what: &str,
    ) -> Result<rusqlite::Transaction<'_>, StudyError> {
        let tx = rusqlite::Transaction::new_unchecked(
            &self.conn,
            rusqlite::TransactionBehavior::Immediate,
        )
        .map_err(db_err(&self.dir))?;
        let now: Option<String> = tx
            .query_row("SELECT value FROM meta WHERE key = 'study_hash'", [], |r| {
                r.get(0)
            })
            .optional()
            .map_err(db_err(&self.dir))?;
        if now.as_deref() != Some(self.hash.as_str()) {
            return Err(StudyError::Busy {
                dir: self.dir.clone(),
                holder: format!(
                    "another study (hash {}, this study {}), started in it by another process; \
                     {what} not stored",
                    now.as_deref().unwrap_or("none"),
                    self.hash,
                ),
            });
        }
        Ok(tx)
    }

    /// Commits a finished run: its row, its fields and, if given, its error estimate, in one
    /// transaction.
    ///
    /// # Errors
    /// As [`Store::commit_group`].
    pub fn commit(
        &self,
        rec: &RunRecord,
        fields: &[f64],
        cre: Option<&[f64]>,
    ) -> Result<(), StudyError> {
        self.commit_group(&[(rec, fields, cre)])
    }

    /// Commits finished runs together (a group of runs solved together): every run's row and
    /// its data (fields, error estimate) in one transaction - one synced database commit for
    /// the group, no file. A committed row therefore always has its data, and the group's rows
    /// are committed all or none.
    ///
    /// # Errors
    /// [`StudyError::Busy`] if the database now holds another study (another process started
    /// one in the directory): the rows are refused, never mixed with the other study's; on I/O
    /// or database errors.
    pub fn commit_group(&self, runs: &[RunToCommit<'_>]) -> Result<(), StudyError> {
        if runs.is_empty() {
            return Ok(());
        }
        // One write transaction, taken at once: the study the directory holds is checked and
        // the rows inserted with no other writer in between.
        let what = if runs.len() == 1 {
            "this run is".to_string()
        } else {
            format!("these {} runs are", runs.len())
        };
        let tx = self.checked_transaction(&what)?;
        {
            let mut row = tx
                .prepare_cached(
                    "INSERT OR REPLACE INTO runs (key, params, status, iterations, residual, seconds, qois, history, state, study_hash, run_hash, quantities, slide_interface, slide_slip, slide_ratio)
                     VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, ?14, ?15)",
                )
                .map_err(db_err(&self.dir))?;
            let mut data = tx
                .prepare_cached(
                    "INSERT OR REPLACE INTO run_data (key, study_hash, fields, cre)
                     VALUES (?1, ?2, ?3, ?4)",
                )
                .map_err(db_err(&self.dir))?;
            let run_hash = self.identity.as_ref().map(|id| id.run_hash.as_str());
            let quantities = self.identity.as_ref().map(|id| id.quantities.join(","));
            for &(rec, fields, cre) in runs {
                let key = point_key(&rec.params);
                row.execute(params![
                    key,
                    to_blob(&rec.params),
                    rec.status,
                    rec.iterations as i64,
                    rec.residual,
                    rec.seconds,
                    to_blob(&rec.qois),
                    to_blob(&rec.history),
                    to_blob(&rec.state),
                    self.hash,
                    run_hash,
                    quantities,
                    rec.slide.as_ref().map(|s| s.interface.as_str()),
                    rec.slide.as_ref().map(|s| s.slip),
                    rec.slide.as_ref().map(|s| s.ratio),
                ])
                .map_err(db_err(&self.dir))?;
                data.execute(params![key, self.hash, to_blob(fields), cre.map(to_blob)])
                    .map_err(db_err(&self.dir))?;
            }
        }
        tx.commit().map_err(db_err(&self.dir))
    }

    /// The `run_data` row of the run at `params`: its study hash and `column` (`None` if the
    /// run has no row: a directory written before the data moved into the database).
    fn data_row<T: rusqlite::types::FromSql>(
        &self,
        params: &[f64],
        column: &str,
    ) -> Result<Option<(String, T)>, StudyError> {
        let sql = match column {
            "fields" => "SELECT study_hash, fields FROM run_data WHERE key = ?1",
            "cre" => "SELECT study_hash, cre FROM run_data WHERE key = ?1",
            _ => return Err(StudyError::Internal(format!("no run_data column {column}"))),
        };
        self.conn
            .prepare_cached(sql)
            .and_then(|mut st| {
                st.query_row(params![point_key(params)], |r| Ok((r.get(0)?, r.get(1)?)))
                    .optional()
            })
            .map_err(db_err(&self.dir))
    }

    /// A [`StudyError::RunData`] for the run at `params`.
    fn data_error(&self, params: &[f64], what: &'static str, why: String) -> StudyError {
        StudyError::RunData {
            dir: self.dir.clone(),
            params: params.to_vec(),
            what,
            why,
        }
    }

    /// The values of a `run_data` BLOB of this study (`hash`), whole f64 values.
    fn untag_blob(
        &self,
        params: &[f64],
        what: &'static str,
        hash: &str,
        b: &[u8],
    ) -> Result<Vec<f64>, StudyError> {
        if hash != self.hash {
            return Err(self.data_error(
                params,
                what,
                format!(
                    "belongs to another study (hash {hash}, this study {}); run again with --restart",
                    self.hash
                ),
            ));
        }
        if !b.len().is_multiple_of(8) {
            return Err(self.data_error(
                params,
                what,
                format!("has {} bytes, not whole values (damaged)", b.len()),
            ));
        }
        Ok(from_blob(b))
    }

    /// Why the stored data of the run at `params` cannot be used, `None` if it can: its field
    /// data must be of this study with `field_values` values, and with `estimate` its
    /// error-estimate data must be present and whole. Reads the sizes only. A run with no
    /// `run_data` row (a directory written before the data moved into the database) is checked
    /// in its files: its field file must exist with `field_values` values (after the
    /// study-hash header of this study, or none for a directory written before headers), and
    /// with `estimate` its error-estimate file must exist with this study's header and whole
    /// values.
    pub fn damaged_files(
        &self,
        params: &[f64],
        field_values: usize,
        estimate: bool,
    ) -> Option<String> {
        // length() of a BLOB reads its size, not its bytes.
        let row = self
            .conn
            .prepare_cached(
                "SELECT study_hash, length(fields), length(cre) FROM run_data WHERE key = ?1",
            )
            .and_then(|mut st| {
                st.query_row(params![point_key(params)], |r| {
                    Ok((
                        r.get::<_, String>(0)?,
                        r.get::<_, Option<i64>>(1)?,
                        r.get::<_, Option<i64>>(2)?,
                    ))
                })
                .optional()
            });
        let (hash, fields, cre) = match row {
            Ok(Some(row)) => row,
            Ok(None) => return self.damaged_legacy_files(params, field_values, estimate),
            Err(e) => return Some(format!("its data cannot be read: {e}")),
        };
        if hash != self.hash {
            return Some(format!(
                "its data belongs to another study (hash {hash}, this study {})",
                self.hash
            ));
        }
        let expected = 8 * field_values as i64;
        let Some(fields) = fields else {
            return Some("its field data is missing".into());
        };
        if fields % 8 != 0 {
            return Some(format!(
                "its field data has {fields} bytes, expected {expected} (truncated or damaged)"
            ));
        }
        if fields != expected {
            return Some(format!(
                "its field data has {} values, expected {field_values} (truncated or damaged)",
                fields / 8
            ));
        }
        if estimate {
            let Some(cre) = cre else {
                return Some("its error-estimate data is missing".into());
            };
            if cre % 8 != 0 {
                return Some(format!(
                    "its error-estimate data has {cre} bytes, not whole values (truncated)"
                ));
            }
        }
        None
    }

    /// [`Store::damaged_files`] for a run stored in files.
    fn damaged_legacy_files(
        &self,
        params: &[f64],
        field_values: usize,
        estimate: bool,
    ) -> Option<String> {
        let header = 8 + 16;
        let name = |p: &Path| p.strip_prefix(&self.dir).unwrap_or(p).display().to_string();
        let fields = self.field_path(params);
        let expected = [header + 8 * field_values as u64, 8 * field_values as u64];
        match std::fs::metadata(&fields) {
            Err(_) => {
                return Some(format!(
                    "its field data is missing (not in the database, and no file {})",
                    name(&fields)
                ));
            }
            Ok(m) if !expected.contains(&m.len()) => {
                return Some(format!(
                    "{} has {} bytes, expected {} (truncated or damaged)",
                    name(&fields),
                    m.len(),
                    expected[0]
                ));
            }
            Ok(m) if m.len() == expected[0] && !self.header_ok(&fields) => {
                return Some(format!("{} has a damaged header", name(&fields)));
            }
            Ok(_) => {}
        }
        if estimate {
            let cre = self.cre_path(params);
            match std::fs::metadata(&cre) {
                Err(_) => {
                    return Some(format!(
                        "its error-estimate data is missing (not in the database, and no file {})",
                        name(&cre)
                    ));
                }
                Ok(m) if m.len() < header || (m.len() - header) % 8 != 0 => {
                    return Some(format!("{} is truncated", name(&cre)));
                }
                Ok(_) if !self.header_ok(&cre) => {
                    return Some(format!("{} has a damaged header", name(&cre)));
                }
                Ok(_) => {}
            }
        }
        None
    }

    /// True if `hash` (a field file's header) is this study's, or one it held before with the
    /// same runs.
    fn is_this_study(&self, hash: &[u8]) -> bool {
        hash == self.hash.as_bytes() || self.former.iter().any(|h| h.as_bytes() == hash)
    }

    /// True if `path` starts with the header of this study.
    fn header_ok(&self, path: &Path) -> bool {
        use std::io::Read;
        let mut head = [0u8; 24];
        std::fs::File::open(path)
            .and_then(|mut f| f.read_exact(&mut head))
            .is_ok()
            && &head[..8] == FIELD_MAGIC
            && self.is_this_study(&head[8..])
    }

    /// A run's error-estimate data (`None` if the run has none).
    ///
    /// # Errors
    /// If it cannot be read, is damaged, or belongs to another study.
    pub fn cre(&self, params: &[f64]) -> Result<Option<Vec<f64>>, StudyError> {
        const WHAT: &str = "error-estimate data";
        if let Some((hash, blob)) = self.data_row::<Option<Vec<u8>>>(params, "cre")? {
            return match blob {
                Some(b) => self.untag_blob(params, WHAT, &hash, &b).map(Some),
                None => Ok(None),
            };
        }
        let path = self.cre_path(params);
        match std::fs::read(&path) {
            Ok(b) => self.untag(&path, &b).map(Some),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
            Err(source) => Err(StudyError::Io { path, source }),
        }
    }

    /// A run's displacement fields (every substructure's, in order).
    ///
    /// # Errors
    /// If they are missing, cannot be read, are damaged, or belong to another study.
    pub fn fields(&self, params: &[f64]) -> Result<Vec<f64>, StudyError> {
        const WHAT: &str = "field data";
        if let Some((hash, b)) = self.data_row::<Vec<u8>>(params, "fields")? {
            return self.untag_blob(params, WHAT, &hash, &b);
        }
        let path = self.field_path(params);
        let b = std::fs::read(&path).map_err(|source| {
            if source.kind() == std::io::ErrorKind::NotFound {
                self.data_error(
                    params,
                    WHAT,
                    format!(
                        "is missing (not in the database, and no file {})",
                        path.display()
                    ),
                )
            } else {
                StudyError::Io {
                    path: path.clone(),
                    source,
                }
            }
        })?;
        match b.strip_prefix(FIELD_MAGIC) {
            Some(_) => self.untag(&path, &b),
            // Written before field files had a header (their rows were migrated above).
            None => Ok(from_blob(&b)),
        }
    }

    /// The values of a file written by the store before the data moved into the database,
    /// checked against this study's hash.
    fn untag(&self, path: &Path, b: &[u8]) -> Result<Vec<f64>, StudyError> {
        match b.strip_prefix(FIELD_MAGIC) {
            Some(rest) if rest.len() >= 16 && (rest.len() - 16) % 8 == 0 => {
                if !self.is_this_study(&rest[..16]) {
                    return Err(StudyError::ForeignFile {
                        path: path.to_path_buf(),
                        hash: String::from_utf8_lossy(&rest[..16]).into_owned(),
                        study: self.hash.clone(),
                    });
                }
                Ok(from_blob(&rest[16..]))
            }
            _ => Err(StudyError::Corrupt {
                path: path.to_path_buf(),
            }),
        }
    }
}
